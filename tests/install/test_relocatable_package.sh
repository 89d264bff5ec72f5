#!/usr/bin/env bash
# The relocatable package (scripts/make-package.sh): laid out, moved into an empty folder, it
# runs a small sweep with the stb image fallback forced and loads nothing from outside itself
# but glibc, glvnd's GL loader and the GL driver (what the loader loads, and what that needs);
# packed, it stays under 64 MiB.
#   test_relocatable_package.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
source=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# With a normal user's PATH (no /usr/sbin, where ldconfig is).
PATH=/usr/local/bin:/usr/bin:/bin bash "$source/scripts/make-package.sh" --build "$build" \
  --stage "$work/staged" > /dev/null
[ -x "$work/staged/run-relieflab" ] || { echo "make-package left no runner"; exit 1; }
mkdir "$work/elsewhere"
mv "$work/staged" "$work/elsewhere/relieflab"  # relocated: no path of the build survives
pkg="$work/elsewhere/relieflab"
[ ! -e "$pkg/lib/librelieflab_oiio.so" ] || { echo "the package carries OpenImageIO's module"; exit 1; }

cat > "$work/sweep.toml" <<TOML
[sweep]
name = "package"
elevations = [30]
viewports = [48]
texture_res = [64]
frames = 1
warmup = 0
[[scene]]
name = "rockwall"
relief = { depth = "$pkg/share/relieflab/assets/relief/rockwall/rockwall_height.bmp", convention = "height" }
depth = 0.08
[[technique]]
name = "relief"
TOML

# The build tree's modules must not be what loads: hide them for the run.
LD_DEBUG=files LD_DEBUG_OUTPUT="$work/ld" RELIEFLAB_IMAGE_MODULE="$pkg/lib/librelieflab_stb.so" \
  RELIEFLAB_CACHE_DIR="$work/cache" "$pkg/run-relieflab" run "$work/sweep.toml" --out "$work/out" -q
grep -q "image files through stb" "$work/out/run.log" || { echo "no stb line in run.log"; exit 1; }
[ "$(wc -l < "$work/out/rows.csv")" -eq 2 ] || { echo "no row"; exit 1; }
grep -q "nvidia-h200" "$work/out/rows.csv" || { echo "no model_gpu in the row"; exit 1; }

# Every library loaded, and who asked for it (LD_DEBUG=files: "file=X [0];  needed by Y" and
# "file=X [0];  dynamically loaded by Y"; where it came from: "calling init: PATH").
python3 - "$work" "$pkg" <<'PY'
import glob, re, sys
work, pkg = sys.argv[1], sys.argv[2]
asked_by, path_of = {}, {}
def name(p): return p.rsplit("/", 1)[-1]
for log in glob.glob(work + "/ld.*"):
    lines = open(log).read().splitlines()
    # Only relieflab's process (the wrapper's shell execs it), not the wrapper's ldconfig or grep.
    if not any(("initialize program: %s/bin/relieflab" % pkg) in l for l in lines):
        continue
    for line in lines:
        m = re.search(r"file=(\S+) \[\d+\];\s+(needed by|dynamically loaded by) (\S+)", line)
        if m:
            asked_by.setdefault(name(m.group(1)), m.group(3))
        m = re.search(r"calling init: (\S+)", line)
        if m:
            path_of.setdefault(name(m.group(1)), m.group(1))
glibc = re.compile(r"^(ld-linux|libc|libm|libdl|libpthread|librt|libresolv|libutil|libmvec|libnss_|libanl)[.-]")
loader = re.compile(r"^lib(EGL|GL|OpenGL|GLX|GLdispatch|GLESv2)\.so")
# The driver: what the GL loader loaded (its vendor library), and all that was asked for from
# there on.
driver = set()
changed = True
while changed:
    changed = False
    for lib, by in asked_by.items():
        path = path_of.get(lib)
        if path is None or path in driver or path.startswith(pkg) or loader.match(name(path)):
            continue
        if (loader.match(name(by)) and not by.startswith(pkg)) or by in driver:
            driver.add(path)
            changed = True
outside = []
for lib, path in path_of.items():
    if path.startswith(pkg) or glibc.match(name(path)) or loader.match(name(path)):
        continue
    if path in driver:
        continue
    outside.append("%s (%s, asked for by %s)" % (lib, path, asked_by.get(lib, "?")))
if not path_of:
    sys.exit("LD_DEBUG wrote nothing to read")
if outside:
    sys.exit("loaded from outside the package:\n  " + "\n  ".join(sorted(outside)))
print("%d libraries loaded: from the package, glibc, the GL loader or the driver (%d)" %
      (len(path_of), len(driver)))
PY

# Without RELIEFLAB_IMAGE_MODULE, through a link to the runner and from a folder of its own: the
# package's own stb module loads (never the build folder's OpenImageIO module, though that path
# exists on this machine), and run.log names the file.
ln -s "$pkg/run-relieflab" "$work/relieflab-link"
RELIEFLAB_CACHE_DIR="$work/cache" "$work/relieflab-link" run "$work/sweep.toml" --out "$work/out2" -q
grep -q "image files through stb.* from $pkg/lib/librelieflab_stb.so" "$work/out2/run.log" ||
  { echo "the package did not load its own stb module:"; grep "image files" "$work/out2/run.log"; exit 1; }

# Without its share/relieflab data the package says so, and reads nothing of the source tree's.
mv "$pkg/share/relieflab/assets" "$work/assets-away"
if RELIEFLAB_CACHE_DIR="$work/cache" "$pkg/run-relieflab" run --out "$work/out3" -q \
  > "$work/nodata.log" 2>&1; then
  echo "the package ran the default sweep without its assets"; exit 1
fi
grep -q "RELIEFLAB_DATA_DIR" "$work/nodata.log" || { cat "$work/nodata.log"; exit 1; }
mv "$work/assets-away" "$pkg/share/relieflab/assets"

# A library cut short (an interrupted copy) is named before anything is loaded.
cp -a "$pkg" "$work/cut"
core=$(ls "$work/cut/lib"/librelieflab_core.so.*.* | head -1)
truncate -s 4096 "$core"
if "$work/cut/run-relieflab" list > "$work/cut.log" 2>&1; then echo "a cut package ran"; exit 1; fi
grep -q "librelieflab_core.so.*the package is incomplete" "$work/cut.log" || { cat "$work/cut.log"; exit 1; }
rm -rf "$work/cut"

# gzip -1 packs looser than make-package's xz -6 (44 MiB where xz -1 gives 31, 2026-12-07),
# in a fifth of xz's time: under 64 MiB here, the shipped archive is too.
size=$(tar -C "$work/elsewhere" -cf - relieflab | gzip -1 | wc -c)
[ "$size" -lt $((64 * 1024 * 1024)) ] || { echo "packs to $size bytes (gzip -1), over 64 MiB"; exit 1; }
echo "package: runs relocated with the stb fallback; packs to $((size / 1024 / 1024)) MiB (gzip -1)"
