# The stress corpus (tests/cli/stress/, made by make_stress.py there), each run through the CLI: inputs valid in
# form whose numbers or work are extreme either complete — with the contacts they must have — or are refused with
# exit 2 and a message that names the cause. Every case runs in well under a second here (tiny meshes; the
# collapse to one point makes 150K contacts); each is held to 60 s so that none can hang CI, ASan included.
# Included from tests/CMakeLists.txt (cli_test: name, expected exit code, regex over stdout+stderr, arguments).
set(ST ${CLI_DIR}/stress)
set(SHEET "contacts vf=22 ee=81.* hash f14149ed75e453c2")  # the folding sheet's contacts, at every scale below
function(stress_test name)
  cli_test(stress.${name} ${ARGN})
  set_tests_properties(cli.stress.${name} PROPERTIES TIMEOUT 60)
endfunction()

# Scales and offsets: exact scalings by 2^±20 and a move 1e9 from the origin answer as the unscaled sheet, for the
# float tester and the exact one; 2^±600 would overflow or underflow the arithmetic and is refused.
stress_test(sheet 0 "${SHEET}" step ${ST}/unit_t0.obj ${ST}/unit_t1.obj)
stress_test(scaled_down_2e20 0 "${SHEET}" step ${ST}/small_t0.obj ${ST}/small_t1.obj)
stress_test(scaled_up_2e20 0 "${SHEET}" step ${ST}/large_t0.obj ${ST}/large_t1.obj)
stress_test(scaled_up_2e20_exact 0 "${SHEET}" step ${ST}/large_t0.obj ${ST}/large_t1.obj --tester exact)
stress_test(far_from_origin 0 "${SHEET}" step ${ST}/far_t0.obj ${ST}/far_t1.obj)
stress_test(underflow 2 "${E}step: the scene's bounding-box diagonal is 3.11e-181, below 1e-30: .*express the scene in a smaller unit" step ${ST}/tiny_t0.obj ${ST}/tiny_t1.obj --candidate-limit 0)
stress_test(overflow 2 "${E}step: coordinates up to 4.15e\\+180, above 1e\\+30: .*express the scene in a larger unit" step ${ST}/huge_t0.obj ${ST}/huge_t1.obj --tester exact)

# Thickness: a tiny one answers as none; one of 1e30 on a built-in scene of 3,248 triangles is refused by its
# estimated work (1,623 candidates per triangle), before any large allocation.
stress_test(thickness_tiny 0 "${SHEET}" step ${ST}/unit_t0.obj ${ST}/unit_t1.obj --tester float:thickness=1e-300)
stress_test(thickness_huge 2 "${E}step: about 5.3e\\+06 candidate triangle pairs expected \\(1623 per triangle of 3248.*thickness 1e\\+30 is" run ${CLI_DIR}/tiny.yaml --no-progress --set scene.resolution=40 --set tester.name=conservative --set tester.thickness=1e30 --set output.dir=out)

# Degenerate frames: every vertex collapsing to one point (every non-adjacent feature pair touches at t = 1), the
# same with every vertex at that point in both frames, every vertex on one line, a single triangle.
stress_test(collapse_to_point 0 "contacts vf=47808 ee=101653.* hash 7b2b7c2a1426210e" step ${ST}/unit_t0.obj ${ST}/point.obj)
stress_test(all_at_one_point 0 "contacts vf=47808 ee=101653.* hash 7b2b7c2a1426210e" step ${ST}/point.obj ${ST}/point.obj --threads 2 --scheduler phc)
stress_test(all_on_one_line 0 "contacts vf=3456 ee=9912.* hash 71ea669f5c6682fe" step ${ST}/line_t0.obj ${ST}/line_t1.obj)
stress_test(one_triangle 0 "contacts vf=0 ee=0" step ${ST}/one_t0.obj ${ST}/one_t1.obj)

# Size: a generated scene of 2M triangles under a 1 GiB memory limit is refused before it is made.
stress_test(two_million_triangles 2 "${E}memory_limit 1.00 GiB: scene drape_fold would have 2000064 triangles" run ${CLI_DIR}/tiny.yaml --set scene.resolution=1000 --set memory_limit=1GiB)
