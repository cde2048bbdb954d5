#!/usr/bin/env bash
# Fails when a commit subject is longer than 72 characters, for every commit since the rule
# holds (4b3da14, 2026-12-05; older subjects stay as they were written). On a shallow clone
# without that commit, checks the commits the clone has.
set -euo pipefail
cd "$(dirname "$0")/.."
base=4b3da14
if ! git rev-parse -q --verify "$base^{commit}" >/dev/null 2>&1; then
  echo "check-commits: $base not in this clone; checking the commits it has" >&2
  range=HEAD
else
  range="$base..HEAD"
fi
long=$(git log --format='%h %s' "$range" | awk '{ s = substr($0, index($0, " ") + 1); if (length(s) > 72) print length(s) " chars: " $0 }')
if [ -n "$long" ]; then
  echo "commit subjects over 72 characters (write a short imperative subject, details in the body):" >&2
  echo "$long" >&2
  exit 1
fi
echo "check-commits: $(git rev-list --count "$range") subjects, none over 72 characters"
