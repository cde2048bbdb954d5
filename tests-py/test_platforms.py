"""The FMUs' platforms: the packed binaries; the win64 DLL run under Wine and the aarch64-linux .so under qemu-user against the x86_64 Linux .so; the FMI 2.0 and FMI 3.0 APIs against each other.

One C program (fmu-crate/tests/c-driver/driver.c) drives the FMI C API; it is compiled natively
with gcc for linux64 and with MinGW-w64 for win64, and the two runs are compared line by line:
every text field equal, every number within 1e-12 relative (floors for quantities that are
zero by symmetry). The libraries differ only in their math library (glibc's libm against
MinGW-w64's/msvcrt's exp, ln, pow); the largest differences are printed (pytest -s). States
serialized on one platform are deserialized on the other. The darwin64 binary cannot run
here; scripts/build-fmu.sh checks its format, architectures, exports, libraries, minimum
macOS and signature when it builds it.

The same driver built with -DECF_FMI3 drives the FMI 3.0 FMU: natively, under Wine, and, built
with Debian's aarch64-linux-gnu-gcc, its aarch64-linux library under qemu-aarch64 (compared
like Windows: the math libraries differ). It prints the field arrays too; apart from them, its
output equals the FMI 2.0 driver's on the same library bit for bit (the version line and the
8 bytes of the FMI 3.0 state's magic aside).
"""

import os
import pathlib
import re
import shutil
import subprocess
import zipfile

import pytest
from fmpy import read_model_description, supported_platforms

ROOT = pathlib.Path(__file__).resolve().parents[1]
DRIVER_DIR = ROOT / "fmu-crate" / "tests" / "c-driver"

# absolute floors of the comparison, in the quantities' units (N, N m, degC, W, 1); with 1e-12 relative
FLOOR = {"Fx": 1e-9, "Fy": 1e-9, "Mz": 1e-9, "P_fric": 1e-9, "T_max": 1e-9, "T_mean": 1e-9,
         # the field arrays of the FMI 3.0 driver (m, Pa, Pa, Pa, degC)
         "field_x": 1e-15, "field_p": 1e-3, "field_tau_x": 1e-3, "field_tau_c2": 1e-3, "field_T": 1e-9}
REL = 1e-12


def qemu() -> str:
    p = shutil.which("qemu-aarch64") or shutil.which("qemu-aarch64-static")
    if not p:
        pytest.fail("qemu-user is not installed: `bash scripts/setup.sh --tests` installs Debian's qemu-user")
    return p


def wine() -> str:
    for c in ("wine64", "/usr/lib/wine/wine64", "wine"):
        p = shutil.which(c) or (c if os.path.isfile(c) and os.access(c, os.X_OK) else None)
        if p:
            return p
    pytest.fail("Wine is not installed: `bash scripts/setup.sh --tests` installs Debian's wine64")


@pytest.fixture(scope="module")
def platforms(fmu_path, tmp_path_factory):
    """The extracted FMU, the driver built for both platforms, and a function that runs one."""
    d = tmp_path_factory.mktemp("platforms")
    with zipfile.ZipFile(fmu_path) as z:
        z.extractall(d / "fmu")
    md = read_model_description(fmu_path)
    for cc, args in (
        ("gcc", ["-o", str(d / "driver"), str(DRIVER_DIR / "driver.c"), "-ldl"]),
        ("x86_64-w64-mingw32-gcc", ["-o", str(d / "driver.exe"), str(DRIVER_DIR / "driver.c")]),
        (
            "x86_64-w64-mingw32-gcc",
            ["-shared", "-o", str(d / "bcryptprimitives.dll"), str(DRIVER_DIR / "bcryptprimitives.c"), "-ladvapi32"],
        ),
    ):
        r = subprocess.run([cc, "-O1", "-Wall", "-Wextra", "-Werror", *args], capture_output=True, text=True)
        assert r.returncode == 0, f"{cc} failed:\n{r.stderr}"
    # the DLL beside the driver and the Wine-only shim (Wine 8.0 lacks bcryptprimitives.dll)
    shutil.copy(d / "fmu" / "binaries" / "win64" / "ecf_contact.dll", d / "ecf_contact.dll")
    res = d / "fmu" / "resources"
    prefix = ROOT / "target" / "wine-prefix"
    prefix.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, WINEPREFIX=str(prefix), WINEDEBUG="-all", WINEDLLOVERRIDES="mscoree,mshtml=")
    w = wine()

    def run(platform: str, *args: str) -> str:
        if platform == "linux64":
            cmd = [str(d / "driver"), str(d / "fmu" / "binaries" / "linux64" / "ecf_contact.so"), md.guid,
                   args[0], res.as_uri(), *args[1:]]
        else:
            # Wine maps the Linux root to drive Z:
            cmd = [w, str(d / "driver.exe"), "ecf_contact.dll", md.guid, args[0], "file:///Z:" + str(res), *args[1:]]
        r = subprocess.run(cmd, cwd=d, env=env, capture_output=True, text=True, timeout=600)
        assert r.returncode == 0, f"{platform} {args}: exit {r.returncode}\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}"
        return r.stdout

    return d, run


@pytest.fixture(scope="module")
def platforms3(fmu3_path, tmp_path_factory):
    """The extracted FMI 3.0 FMU, the FMI 3.0 driver for x86_64-linux, x86_64-windows and aarch64-linux, and a function that runs one."""
    d = tmp_path_factory.mktemp("platforms3")
    with zipfile.ZipFile(fmu3_path) as z:
        z.extractall(d / "fmu")
    md = read_model_description(fmu3_path)
    src = str(DRIVER_DIR / "driver.c")
    for cc, args in (
        ("gcc", ["-o", str(d / "driver"), src, "-ldl"]),
        ("gcc", ["-UECF_FMI3", "-o", str(d / "driver2"), src, "-ldl"]),
        ("x86_64-w64-mingw32-gcc", ["-o", str(d / "driver.exe"), src]),
        ("aarch64-linux-gnu-gcc", ["-o", str(d / "driver-arm64"), src, "-ldl"]),
        (
            "x86_64-w64-mingw32-gcc",
            ["-shared", "-o", str(d / "bcryptprimitives.dll"), str(DRIVER_DIR / "bcryptprimitives.c"), "-ladvapi32"],
        ),
    ):
        fmi3 = [] if "-UECF_FMI3" in args or "-shared" in args else ["-DECF_FMI3"]
        r = subprocess.run([cc, "-O1", "-Wall", "-Wextra", "-Werror", *fmi3, *args], capture_output=True, text=True)
        assert r.returncode == 0, f"{cc} failed:\n{r.stderr}"
    shutil.copy(d / "fmu" / "binaries" / "x86_64-windows" / "ecf_contact.dll", d / "ecf_contact.dll")
    res = d / "fmu" / "resources"
    prefix = ROOT / "target" / "wine-prefix"
    prefix.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, WINEPREFIX=str(prefix), WINEDEBUG="-all", WINEDLLOVERRIDES="mscoree,mshtml=")
    lib = d / "fmu" / "binaries"

    def run(platform: str, *args: str) -> str:
        # FMI 3.0 passes the resources folder as a path (with its trailing separator)
        if platform == "x86_64-linux":
            cmd = [str(d / "driver"), str(lib / "x86_64-linux" / "ecf_contact.so"), md.instantiationToken,
                   args[0], str(res) + "/", *args[1:]]
        elif platform == "aarch64-linux":
            cmd = [qemu(), "-L", "/usr/aarch64-linux-gnu", str(d / "driver-arm64"),
                   str(lib / "aarch64-linux" / "ecf_contact.so"), md.instantiationToken, args[0], str(res) + "/", *args[1:]]
        else:
            cmd = [wine(), str(d / "driver.exe"), "ecf_contact.dll", md.instantiationToken, args[0],
                   "Z:" + str(res) + "/", *args[1:]]
        r = subprocess.run(cmd, cwd=d, env=env, capture_output=True, text=True, timeout=1800)
        assert r.returncode == 0, f"{platform} {args}: exit {r.returncode}\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}"
        return r.stdout

    return d, run, md


def compare(lin: str, win: str, what: str) -> dict:
    """Asserts the two outputs agree (text equal, numbers within REL or the floors); returns the worst relative difference per quantity."""
    a, b = lin.splitlines(), win.splitlines()
    assert len(a) == len(b), f"{what}: {len(a)} lines on linux64, {len(b)} on win64"
    worst = {}
    for la, lb in zip(a, b):
        ta, tb = la.split(), lb.split()
        assert len(ta) == len(tb), f"{what}:\n{la}\n{lb}"
        for i, (x, y) in enumerate(zip(ta, tb)):
            if x == y:
                continue
            try:
                fx, fy = float(x), float(y)
            except ValueError:
                pytest.fail(f"{what}: text differs: '{x}' against '{y}' in\n{la}\n{lb}")
            # the field arrays: the line's second word names them; scalars follow their name
            name = ta[1] if ta[1].startswith("field_") else ta[i - 1]
            scale = max(abs(fx), abs(fy))
            assert abs(fx - fy) <= REL * scale + FLOOR.get(name, 0.0), f"{what}: {name} {x} (linux64) vs {y} (win64) in\n{la}"
            worst[name] = max(worst.get(name, 0.0), abs(fx - fy) / scale if scale else 0.0)
    return worst


def test_the_fmu_carries_linux64_win64_and_darwin64(fmu_path):
    # fmpy reads the platforms from the binaries/ folder names of FMI 2.0
    assert sorted(supported_platforms(fmu_path)) == ["darwin64", "linux64", "win64"]
    with zipfile.ZipFile(fmu_path) as z:
        names = set(z.namelist())
        dll = z.read("binaries/win64/ecf_contact.dll")
        dylib = z.read("binaries/darwin64/ecf_contact.dylib")
    assert {"binaries/linux64/ecf_contact.so", "binaries/win64/ecf_contact.dll", "binaries/darwin64/ecf_contact.dylib"} <= names
    # PE: "MZ", the PE header's machine field 0x8664 (x86-64); Mach-O universal: 0xcafebabe with 2 architectures
    pe = int.from_bytes(dll[0x3C:0x40], "little")
    assert dll[:2] == b"MZ" and dll[pe : pe + 4] == b"PE\0\0" and dll[pe + 4 : pe + 6] == b"\x64\x86"
    assert dylib[:4] == b"\xca\xfe\xba\xbe" and int.from_bytes(dylib[4:8], "big") == 2


def test_win64_under_wine_gives_the_linux64_results(platforms):
    _, run = platforms
    lin = run("linux64", "run")
    win = run("win64", "run")
    # the scenarios ran and checked themselves on both platforms
    for out in (lin, win):
        assert "failures 0" in out
        assert "state set-state-continuation identical serialize-continuation identical" in out
        assert "bad-input preset status-error logged yes mentions-value yes" in out
        assert "bad-input v=NaN status-error logged yes names-v yes" in out
        # every scenario reached its last step (config_file_relative: resolved against the resources URI)
        for last in ("table4.1_20mps_0.1ms step 40", "dry_5mps_1ms step 20", "wet_30mps_1ms_threads2 step 20",
                     "dry_20mps_0.1ms_continuous step 40", "fastsim_10mps_1ms step 10", "polach_10mps_1ms step 5",
                     "config_file_relative_1ms step 10", "state step 20"):
            assert last + " " in out, last
    worst = compare(lin, win, "run")
    print("largest relative differences win64 vs linux64:", {k: f"{v:.1e}" for k, v in sorted(worst.items())})


def test_states_serialized_on_one_platform_continue_on_the_other(platforms):
    d, run = platforms
    save_lin = run("linux64", "save", str(d / "linux.state"))
    save_win = run("win64", "save", "windows.state")
    assert (d / "linux.state").stat().st_size == (d / "windows.state").stat().st_size > 0
    # same platform: the continuation from the deserialized state is the saved run's, bit for bit
    assert run("linux64", "load", str(d / "linux.state")) == save_lin
    assert run("win64", "load", "windows.state") == save_win
    # across platforms: within the math libraries' differences
    w1 = compare(save_lin, run("win64", "load", "linux.state"), "linux64 state on win64")
    w2 = compare(run("linux64", "load", str(d / "windows.state")), save_win, "win64 state on linux64")
    assert re.search(r"saveload step 40 ", save_lin)
    print("state across platforms, largest relative differences:", {k: f"{max(w1.get(k, 0), w2.get(k, 0)):.1e}" for k in set(w1) | set(w2)})


def test_the_fmi3_fmu_carries_five_platform_tuples(fmu3_path):
    with zipfile.ZipFile(fmu3_path) as z:
        libs = sorted(n for n in z.namelist() if n.startswith("binaries/"))
        arm = z.read("binaries/aarch64-linux/ecf_contact.so")
        mac = [z.read(f"binaries/{a}-darwin/ecf_contact.dylib") for a in ("x86_64", "aarch64")]
    assert libs == ["binaries/aarch64-darwin/ecf_contact.dylib", "binaries/aarch64-linux/ecf_contact.so",
                    "binaries/x86_64-darwin/ecf_contact.dylib", "binaries/x86_64-linux/ecf_contact.so",
                    "binaries/x86_64-windows/ecf_contact.dll"]
    # ELF64 little endian, e_machine 183 (AArch64); thin Mach-O 64 of CPU x86_64 (0x01000007) and arm64 (0x0100000c)
    assert arm[:4] == b"\x7fELF" and arm[4] == 2 and int.from_bytes(arm[18:20], "little") == 183
    assert [m[:4] for m in mac] == [b"\xcf\xfa\xed\xfe"] * 2
    assert [int.from_bytes(m[4:8], "little") for m in mac] == [0x01000007, 0x0100000C]


def _strip_field(out: str) -> list:
    return [line for line in out.splitlines() if " field_" not in line]


def test_fmi3_on_windows_and_aarch64_linux_gives_the_x86_64_linux_results(platforms3):
    _, run, _ = platforms3
    lin = run("x86_64-linux", "run")
    others = {p: run(p, "run") for p in ("x86_64-windows", "aarch64-linux")}
    for out in (lin, *others.values()):
        assert out.startswith("GetVersion 3.0\n") and "failures 0" in out
        assert "state set-state-continuation identical serialize-continuation identical" in out
        assert "table4.1_20mps_0.1ms field_tau_x " in out and "polach_10mps_1ms field_regime " + " ".join(["-1"] * 80) in out
    for p, out in others.items():
        worst = compare(lin, out, f"fmi3 {p}")
        print(f"largest relative differences {p} vs x86_64-linux:", {k: f"{v:.1e}" for k, v in sorted(worst.items())})


def test_the_fmi3_api_gives_the_fmi2_apis_results_bit_for_bit(platforms3, fmu_path):
    d, run, _ = platforms3
    lin3 = run("x86_64-linux", "run")
    md2 = read_model_description(fmu_path)
    with zipfile.ZipFile(fmu_path) as z:
        z.extract("binaries/linux64/ecf_contact.so", d / "fmu2")
    r = subprocess.run([str(d / "driver2"), str(d / "fmu2" / "binaries" / "linux64" / "ecf_contact.so"), md2.guid, "run",
                        (d / "fmu" / "resources").as_uri() + "/"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-3000:]
    a, b = _strip_field(lin3), r.stdout.splitlines()
    assert (a[0], b[0]) == ("GetVersion 3.0", "GetVersion 2.0")
    # the FMI 3.0 state is the FMI 2.0 state after 8 bytes of its own magic
    sa, sb = [next(x for x in o if x.startswith("state set-state")) for o in (a, b)]
    assert int(sa.split()[-1]) == int(sb.split()[-1]) + 8
    assert [x for x in a[1:] if x != sa] == [x for x in b[1:] if x != sb]


def test_fmi3_states_serialized_on_one_platform_continue_on_the_others(platforms3):
    d, run, _ = platforms3
    saves = {p: run(p, "save", f"{p}.state") for p in ("x86_64-linux", "aarch64-linux")}
    assert (d / "x86_64-linux.state").stat().st_size == (d / "aarch64-linux.state").stat().st_size > 0
    assert run("aarch64-linux", "load", "aarch64-linux.state") == saves["aarch64-linux"]
    compare(saves["x86_64-linux"], run("aarch64-linux", "load", "x86_64-linux.state"), "x86_64 state on aarch64")
    compare(run("x86_64-linux", "load", "aarch64-linux.state"), saves["aarch64-linux"], "aarch64 state on x86_64")
