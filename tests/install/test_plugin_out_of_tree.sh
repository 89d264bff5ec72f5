#!/usr/bin/env bash
# Installs ReliefLab under a throwaway prefix, builds examples/plugin/ from a copy outside the
# repository against it (find_package(ReliefLab)), and checks that the installed relieflab lists
# the plugin's technique, from --plugins and from $RELIEFLAB_PLUGIN_PATH, and sweeps it against
# the truth with the installed assets (the source tree is not on any path it is given).
#   test_plugin_out_of_tree.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
src=$2
work=$(mktemp -d)
trap '[ -n "${KEEP_WORK:-}" ] || rm -rf "$work"' EXIT
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" >"$work/install.log"
cp -r "$src/examples/plugin" "$work/plugin"
cmake -S "$work/plugin" -B "$work/plugin-build" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" >"$work/configure.log" ||
  { cat "$work/configure.log"; exit 1; }
cmake --build "$work/plugin-build" -j2 >"$work/build.log" || { cat "$work/build.log"; exit 1; }
plugin=$work/plugin-build/librelieflab_interval_mapping.so
test -f "$plugin" || { echo "no $plugin"; ls "$work/plugin-build"; exit 1; }

relieflab=$prefix/bin/relieflab
expect() {  # expect TEXT FILE: FILE holds TEXT
  grep -qF -- "$1" "$2" || { echo "expected '$1' in:"; cat "$2"; exit 1; }
}
"$relieflab" list >"$work/list-builtin.txt"
if grep -q interval_mapping "$work/list-builtin.txt"; then
  echo "interval_mapping listed without the plugin loaded"; exit 1
fi
"$relieflab" list --plugins "$work/plugin-build" >"$work/list.txt"
expect "interval_mapping — Interval mapping (linear search + regula falsi)" "$work/list.txt"
expect "plugin:   $plugin" "$work/list.txt"
RELIEFLAB_PLUGIN_PATH=$work/plugin-build "$relieflab" list >"$work/list-env.txt"
expect "interval_mapping — Interval mapping" "$work/list-env.txt"

# A sweep of the plugin beside a built-in technique, on the installed rock wall (a path
# relative to the data folder) and a procedural map; run from a folder that holds nothing.
cat >"$work/sweep.toml" <<'TOML'
[sweep]
name = "plugin_sweep"
elevations = [45, 20]
azimuths = [30]
viewports = [64]
frames = 1
warmup = 0
images = false

[[scene]]
name = "rockwall"
relief = { depth = "assets/relief/rockwall/rockwall_height.bmp", convention = "height" }
depth = 0.08

[[scene]]
name = "bricks"
relief = { procedural = "bricks", resolution = 128 }
depth = 0.08

[[technique]]
name = "interval_mapping"
linear_steps = [8, 32]
secant_steps = [3]

[[technique]]
name = "relief"
linear_steps = [32]
binary_steps = [6]
TOML
mkdir "$work/empty"
(cd "$work/empty" && "$relieflab" run "$work/sweep.toml" --out "$work/out" -q \
  --plugins "$plugin") >"$work/run.log" 2>&1 || { cat "$work/run.log"; exit 1; }
rows=$(grep -c '^interval_mapping,\|,interval_mapping,' "$work/out/rows.csv" || true)
test "$rows" -eq 8 || { echo "expected 8 interval_mapping rows, got $rows:"; head -3 "$work/out/rows.csv"; exit 1; }
# Run again into the same folder: every row reused. Then the plugin rebuilt with an edited
# shader (its linear search one step shorter): its 8 rows are measured again, relief's 4 kept.
sweep_again() {
  (cd "$work/empty" && "$relieflab" run "$work/sweep.toml" --out "$work/out" -q \
    --plugins "$plugin") >"$1" 2>&1 || { cat "$1"; exit 1; }
}
sweep_again "$work/again.log"
expect "relieflab: 12 row(s) reused" "$work/again.log"
sed -i 's/for (int i = 1; i < RL_LINEAR_STEPS; i++)/for (int i = 1; i < RL_LINEAR_STEPS - 1; i++)/' \
  "$work/plugin/interval_mapping.glsl"
cmake --build "$work/plugin-build" -j2 >"$work/rebuild.log" || { cat "$work/rebuild.log"; exit 1; }
sweep_again "$work/edited.log"
expect "relieflab: 4 row(s) reused; 8 re-measured: " "$work/edited.log"
expect "the programs of technique interval_mapping changed (8)" "$work/edited.log"

# Without the plugin the same config is refused, naming the technique.
if (cd "$work/empty" && "$relieflab" run "$work/sweep.toml" --out "$work/out2" -q) \
  >"$work/refused.log" 2>&1; then
  echo "the sweep ran without its plugin"; exit 1
fi
expect "unknown technique 'interval_mapping'" "$work/refused.log"

# The installed package holds the plugin to what its describe() declares, as `ctest -L contract`
# holds the built-in techniques: `relieflab contract` with the plugin loaded runs its techniques.
"$relieflab" contract --plugins "$work/plugin-build" >"$work/contract.log" 2>&1 ||
  { cat "$work/contract.log"; exit 1; }
expect "/interval_mapping" "$work/contract.log"
if grep -q "/relief_exact " "$work/contract.log"; then
  echo "contract held built-in techniques it was not asked for"; cat "$work/contract.log"; exit 1
fi
if "$relieflab" contract --technique no_such >"$work/contract-unknown.log" 2>&1; then
  echo "contract accepted an unknown technique"; exit 1
fi
expect "no technique 'no_such'" "$work/contract-unknown.log"
passed=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$work/contract.log")
test "${passed:-0}" -ge 5 || { echo "contract ran ${passed:-0} tests:"; cat "$work/contract.log"; exit 1; }
echo "plugin built out of tree, listed, swept ($rows rows) and held to its contract ($passed tests)"
