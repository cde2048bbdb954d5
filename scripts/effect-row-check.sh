#!/usr/bin/env bash
# Checks that an effect is one row of creep-core's catalogue: on a scratch copy of the work
# tree (tracked files), adds an effect `scratch_trial` (a variant of `Effect` and its row of
# `CATALOGUE` in creep-core/src/effects.rs, nothing else) and runs
# `cargo check --workspace --all-targets`. It passes when that compiles: no other file (the
# CLI, the FMU, the diagnosis of ecf-measure) has to name the new effect. Its physics and the
# regenerated modelDescription.xml are the other things a real effect adds
# (docs/ARCHITECTURE.md, "Where each kind of change goes").
#   bash scripts/effect-row-check.sh     a check build of the workspace: minutes, not seconds
# The scratch copy is removed at the end; its build goes to $CARGO_TARGET_DIR/effect-row-check
# (default target/effect-row-check).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
git ls-files -z | xargs -0 tar -cf - | tar -xf - -C "$tmp"
python3 - "$tmp/creep-core/src/effects.rs" <<'PY'
import sys
path = sys.argv[1]
s = open(path).read()
enum = "pub enum Effect {\n"
i = s.index(enum)
j = s.index("\n}\n", i)
s = s[:j] + "\n    /// A scratch effect of scripts/effect-row-check.sh.\n    ScratchTrial," + s[j:]
k = s.index("pub const CATALOGUE: &[EffectInfo] = &[")
m = s.index("\n];\n", k)
row = """
    EffectInfo {
        effect: Effect::ScratchTrial,
        name: "scratch_trial",
        vr: 58,
        description: "A scratch effect.",
        params: &[P::Mu],
        fit: &[P::Mu],
        signature: &["v_mps"],
        applies: Applies::Always,
    },"""
s = s[:m] + row + s[m:]
open(path, "w").write(s)
PY
echo "== effect-row-check: added Effect::ScratchTrial and its row (creep-core/src/effects.rs) on a scratch copy" >&2
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}/effect-row-check"
if (cd "$tmp" && cargo check -q --workspace --all-targets); then
  echo "effect-row-check: ok, the row alone compiles; no other file names the new effect"
else
  echo "effect-row-check: FAILED, the files cargo names above must change for a new effect" >&2
  exit 1
fi
