#!/usr/bin/env bash
# Makes a relocatable ReliefLab package: the CLI, its libraries and every library they need but
# glibc, with the stb image module that stands in where OpenImageIO cannot be carried, so that a
# machine with only a GPU driver (and glibc) can run a config and bring rows back.
#
#   scripts/make-package.sh [--build DIR] [--out FILE.tar.xz | --stage DIR]
#
# --build: the CMake build folder (default build); --out: the archive (default
# relieflab-package.tar.xz); --stage: lay the package out in DIR and make no archive.
# On the other machine: tar xf FILE && relieflab/run-relieflab run CONFIG --out DIR
# (run-relieflab sets the library path and, where the system has none, glvnd's GL loader).
#
# What stays outside: glibc (libc, libm, ld-linux, ...), the GL driver and everything it loads.
# glvnd's loader (libEGL, libOpenGL, libGL, libGLX, libGLdispatch) travels in lib/glvnd/ and is
# used only where the system lacks a part of it. OpenImageIO's module is left out: its ~260 libraries
# (363 MB) are the package's obstacle; images then go through librelieflab_stb.so.
set -euo pipefail

build=build
out=relieflab-package.tar.xz
stage=""
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --stage) stage="$2"; shift 2 ;;
    *) echo "make-package: unknown argument '$1' (--build DIR, --out FILE, --stage DIR)" >&2; exit 2 ;;
  esac
done
[ -x "$build/relieflab" ] || { echo "make-package: no built CLI at $build/relieflab" >&2; exit 2; }
# ldconfig is in /sbin, which a normal user's PATH may not hold.
PATH="$PATH:/usr/sbin:/sbin"

work=""
if [ -z "$stage" ]; then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  stage="$work/relieflab"
fi
[ ! -e "$stage" ] || [ -z "$(ls -A "$stage")" ] || {
  echo "make-package: $stage exists and is not empty" >&2
  exit 2
}
mkdir -p "$stage"
stage=$(cd "$stage" && pwd)

cmake --install "$build" --prefix "$stage" > /dev/null
rm -rf "$stage/include" "$stage/lib/cmake" "$stage/lib/librelieflab_oiio.so"

# glibc's libraries and the GL loader: the machine's own, never copied into lib/.
is_system() {
  case "$1" in
    ld-linux*|libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|libresolv.so*|libutil.so*) return 0 ;;
    libmvec.so*|libanl.so*|libnss_*|libBrokenLocale.so*) return 0 ;;
    libEGL.so*|libGL.so*|libOpenGL.so*|libGLX.so*|libGLdispatch.so*|libGLESv2.so*) return 0 ;;
  esac
  return 1
}

# The closure of everything in bin/ and lib/, as the loader resolves it here.
LD_LIBRARY_PATH="$stage/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
  ldd "$stage/bin/relieflab" "$stage"/lib/*.so* "$stage"/lib/relieflab/* 2>/dev/null |
  awk '$2 == "=>" && $3 ~ /^\// { print $3 }' | sort -u |
  while read -r lib; do
    name=$(basename "$lib")
    is_system "$name" && continue
    [ -e "$stage/lib/$name" ] || cp -L "$lib" "$stage/lib/$name"
  done

# glvnd's loader, for a machine whose driver came without it (an NVIDIA container's, say).
mkdir -p "$stage/lib/glvnd"
for name in libEGL.so.1 libOpenGL.so.0 libGL.so.1 libGLX.so.0 libGLdispatch.so.0; do
  # awk reads to the end: leaving early would kill ldconfig with SIGPIPE, which pipefail and
  # set -e turn into a silent exit of this script.
  path=$(ldconfig -p | awk -v n="$name" '$1 == n && /x86-64/ && !found { print $NF; found = 1 }')
  [ -n "$path" ] && cp -L "$path" "$stage/lib/glvnd/$name"
done

# Every file's size, so that a package cut short (an interrupted copy or extraction) is named
# before it is run, not met as a SIGBUS when the loader maps a truncated library.
(cd "$stage" && find bin lib -type f -printf '%s %p\n' | sort -k2) > "$stage/SIZES"

cat > "$stage/run-relieflab" <<'EOF'
#!/bin/sh
# Runs the packaged relieflab with the package's libraries; arguments go to relieflab. Called
# through a link too: the package is where the script itself lies.
here=$(cd "$(dirname "$(readlink -f "$0")")" && pwd)
PATH="$PATH:/usr/sbin:/sbin"
if ! (cd "$here" && find bin lib -type f -printf '%s %p\n' | sort -k2) | cmp -s - "$here/SIZES"; then
  while read -r size file; do
    actual=$(stat -c %s "$here/$file" 2>/dev/null || echo "no")
    if [ "$actual" != "$size" ]; then
      echo "run-relieflab: $here/$file has $actual bytes where the package made $size: the" \
        "package is incomplete (an interrupted copy or extraction?); unpack it again" >&2
      exit 3
    fi
  done < "$here/SIZES"
fi
libs="$here/lib"
# glvnd's loader from the package only where the system lacks a part of it.
for lib in libEGL.so.1 libOpenGL.so.0 libGL.so.1 libGLX.so.0 libGLdispatch.so.0; do
  if ! ldconfig -p 2>/dev/null | grep -q "$lib "; then libs="$libs:$here/lib/glvnd"; break; fi
done
# The NVIDIA driver's EGL vendor file, where the system's glvnd folder does not list it.
if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ] && ! ls /usr/share/glvnd/egl_vendor.d/*.json >/dev/null 2>&1; then
  for f in /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json /etc/glvnd/egl_vendor.d/10_nvidia.json; do
    [ -e "$f" ] && export __EGL_VENDOR_LIBRARY_FILENAMES="$f" && break
  done
fi
LD_LIBRARY_PATH="$libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" exec "$here/bin/relieflab" "$@"
EOF
chmod +x "$stage/run-relieflab"

if [ -n "$work" ]; then
  # Under a temporary name, renamed when whole: a kill leaves no archive that looks finished.
  trap 'rm -rf "$work" "$out.partial.$$"' EXIT
  tar -C "$work" -cf - relieflab | xz -T0 -6 > "$out.partial.$$"
  mv -f "$out.partial.$$" "$out"
  echo "make-package: $out ($(du -h "$out" | cut -f1); $(du -sh "$stage" | cut -f1) unpacked)"
else
  echo "make-package: staged in $stage ($(du -sh "$stage" | cut -f1))"
fi
