#!/usr/bin/env bash
# The installed package, used as a stranger would (docs/embedding.md): `cmake --install` into a fresh prefix,
# no build-tree path in what was installed, examples/step_contacts copied outside the repository and built
# against it with find_package(ccdlab), its contacts equal to the installed CLI's (`ccdlab step --contacts`:
# the same pairs, times, coordinates and normals) on the shared real steps, or on a small built-in pair of
# frames where ../shared/data is absent; examples/mass_spring_cloth built the same way and kept collision-free
# by earliest_toi; examples/barrier_cloth (the proximity query and step size in a barrier solver) ends every frame
# separated; and the installed Python module imports and answers.
# Usage: tests/install/consumer.sh [BUILD_DIR]   (default: build, the release preset's)
set -euo pipefail
cd "$(dirname "$0")/../.."
repo="$PWD"
build="$(cd "${1:-build}" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"

cmake --install "$build" --prefix "$prefix" >/dev/null
if grep -rlF -e "$repo" -e "$build" "$prefix/lib/cmake" "$prefix/include"; then
  echo "FAIL: the installed package names build-tree paths (files above)"; exit 1
fi

cp -r examples/step_contacts "$work/src"
cmake -S "$work/src" -B "$work/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/build" >/dev/null
consumer="$work/build/step_contacts"

same_contacts() {  # CSV of the consumer vs the CLI's: the same rows (as numbers), in any order
  /usr/bin/python3 - "$1" "$2" <<'PY'
import csv, sys
def rows(path):
    with open(path) as f:
        return sorted((r[0], *map(int, r[1:5]), *map(float, r[5:])) for r in list(csv.reader(f))[1:])
a, b = rows(sys.argv[1]), rows(sys.argv[2])
if a != b:
    sys.exit(f"FAIL: {len(a)} contacts from the consumer, {len(b)} from the CLI, or different values")
print(f"  {len(a)} contacts, identical")
PY
}

data="../shared/data/meshes"
pairs=()
if [ -d "$data" ]; then
  pairs=("$data/rod-twist/3036.ply $data/rod-twist/3037.ply" "$data/cloth-funnel/227.ply $data/cloth-funnel/228.ply"
         "$data/n-body-simulation/balls16_18.ply $data/n-body-simulation/balls16_19.ply")
else
  echo "../shared/data not found: the consumer is compared with the CLI on a built-in pair of frames only"
fi
# Built in: a vertex falling through a triangle, and an edge crossing another.
cat > "$work/a.obj" <<'OBJ'
v 0 0 0
v 1 0 0
v 0 1 0
v 0.2 0.2 1
v 0.2 0.2 2
v 1 1 1
v 3 0 0.5
v 3 1 0.5
v 4 0 0.5
OBJ
sed -e 's/^v 0.2 0.2 1$/v 0.2 0.2 -1/' -e 's/^v 3 0 0.5$/v 3 0 -0.5/' "$work/a.obj" > "$work/b.obj"
printf 'f 1 2 3\nf 4 5 6\nf 7 8 9\n' | tee -a "$work/a.obj" >> "$work/b.obj"
pairs+=("$work/a.obj $work/b.obj")

for pair in "${pairs[@]}"; do
  read -r t0 t1 <<<"$pair"
  echo "$(basename "$t0") → $(basename "$t1"):"
  for options in "" "{scheduler: phc, threads: 2}"; do
    "$consumer" "$t0" "$t1" "$options" > "$work/api.csv" 2>/dev/null
    "$prefix/bin/ccdlab" step "$t0" "$t1" --contacts "$work/cli.csv" \
      $( [ -n "$options" ] && echo "--scheduler phc --threads 2" ) >/dev/null
    same_contacts "$work/api.csv" "$work/cli.csv"
  done
done
[ "$(wc -l < "$work/api.csv")" -gt 1 ] || { echo "FAIL: no contact on the built-in frames"; exit 1; }

# Errors reach the consumer as ccdlab::Error, naming the call and the file.
if "$consumer" "$work/missing.ply" "$work/b.obj" 2> "$work/err.txt"; then echo "FAIL: a missing file was accepted"; exit 1; fi
grep -q "ccdlab::read_mesh: .*missing.ply" "$work/err.txt" || { echo "FAIL: unexpected message: $(cat "$work/err.txt")"; exit 1; }
if "$consumer" "$work/a.obj" "$work/b.obj" "{sheduler: phc}" 2> "$work/err.txt"; then echo "FAIL: a mistyped option was accepted"; exit 1; fi
grep -q "OPTIONS_YAML:1: .*sheduler" "$work/err.txt" || { echo "FAIL: unexpected message: $(cat "$work/err.txt")"; exit 1; }

# The mass-spring example: earliest_toi keeps every frame collision-free; the cloth reaches the floor, never below.
cp -r examples/mass_spring_cloth "$work/cloth"
cmake -S "$work/cloth" -B "$work/cloth/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/cloth/build" >/dev/null
"$work/cloth/build/mass_spring_cloth" > "$work/cloth.txt"
/usr/bin/python3 - "$work/cloth.txt" <<'PY'
import re, sys
lines = open(sys.argv[1]).read().splitlines()
z = [float(re.search(r"z = (\S+)", l).group(1)) for l in lines]
t = [float(re.search(r"impact (\S+),", l).group(1)) for l in lines]
if not z or min(z) < 0 or min(t) >= 1 or z[-1] > 0.05:
    sys.exit("FAIL: mass_spring_cloth: " + " | ".join(lines[-3:]))
print(f"  mass_spring_cloth: {len(lines)} reports, lowest point {min(z):.5f}, earliest impact {min(t):.4f}")
PY

# The barrier-solver example: every Newton iteration asks for the active set and the step size; every frame ends
# with no pair closer than the separation (the example checks it, exit 1 otherwise); the cloth comes to rest on the
# floor (z = -0.25), not below it.
cp -r examples/barrier_cloth "$work/barrier"
cmake -S "$work/barrier" -B "$work/barrier/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/barrier/build" >/dev/null
"$work/barrier/build/barrier_cloth" 30 > "$work/barrier.txt"
/usr/bin/python3 - "$work/barrier.txt" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
z = [float(v) for v in re.findall(r"lowest cloth point z = (\S+),", text)]
if "30 frames, every one separated by at least" not in text or not z or min(z) < -0.25 or z[-1] > -0.2:
    sys.exit("FAIL: barrier_cloth: " + text[-400:])
print(f"  barrier_cloth: 30 frames separated, lowest point {min(z):.4f}")
PY
# The same with the `additive` tester's step size in the line search (not conservative: whether every frame stays
# separated is reported, not required); the run must finish and print its comparison line.
"$work/barrier/build/barrier_cloth" 30 additive > "$work/barrier_additive.txt" 2>&1 || true
/usr/bin/python3 - "$work/barrier.txt" "$work/barrier_additive.txt" <<'PY'
import re, sys
for f in sys.argv[1:]:
    text = open(f).read()
    m = re.search(r"line search: .*", text) or re.search(r"frame \d+ ends with pairs closer than the separation", text)
    if not m:
        sys.exit("FAIL: barrier_cloth: neither a line-search summary nor a separation failure: " + text[-400:])
    print("  barrier_cloth " + m.group(0))
PY

PYTHONPATH="$prefix/lib/python3/dist-packages" /usr/bin/python3 -c '
import ccdlab, numpy as np
x0 = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0.2, 0.2, 1], [0.2, 0.2, 2], [1, 1, 1]], float)
x1 = x0.copy(); x1[3, 2] = -1
r = ccdlab.step(x0, x1, np.array([[0, 1, 2], [3, 4, 5]]))
assert len(r["vf"]) >= 1, r
print("  the installed Python module:", len(r["vf"]), "VF contact(s)")'
echo "consumer test passed"
