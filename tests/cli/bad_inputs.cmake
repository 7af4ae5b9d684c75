# The corpus of bad inputs (tests/cli/bad_inputs/, made by make_corpus.py there), each run through the CLI:
# a user's mistake exits 2 with one "ccdlab: error:" line naming the file (and line or element, where there is
# one); awkward but valid files (CRLF, a byte-order mark, a non-manifold edge) are read as their plain twins.
# Included from tests/CMakeLists.txt (cli_test: name, expected exit code, regex over stdout+stderr, arguments).
set(BAD ${CLI_DIR}/bad_inputs)
set(T0 ${CLI_DIR}/fall_t0.obj)
set(E "ccdlab: error: ")

# OBJ
cli_test(bad.obj_empty 2 "${E}.*empty.obj: empty file" step ${T0} ${BAD}/empty.obj)
cli_test(bad.obj_no_faces 2 "${E}.*no_faces.obj: no faces" step ${BAD}/no_faces.obj ${BAD}/no_faces.obj)
cli_test(bad.obj_nan 2 "${E}.*nan.obj:5: vertex 4: non-finite coordinate \\(0.6 nan 1\\)" step ${T0} ${BAD}/nan.obj)
cli_test(bad.obj_inf 2 "${E}.*inf.obj:3: vertex 2: non-finite coordinate \\(0 inf 0\\)" step ${T0} ${BAD}/inf.obj)
cli_test(bad.obj_index_out_of_range 2 "${E}.*index_out_of_range.obj:8: face: vertex index 6 out of range \\[0, 6\\)" step ${T0} ${BAD}/index_out_of_range.obj)
cli_test(bad.obj_negative_index 2 "${E}.*negative_index_out_of_range.obj:8: face: vertex index -3 out of range" step ${T0} ${BAD}/negative_index_out_of_range.obj)
cli_test(bad.obj_zero_index 2 "${E}.*zero_index.obj:7: face: expected a vertex index, got '0'" step ${T0} ${BAD}/zero_index.obj)
cli_test(bad.obj_degenerate_face 2 "${E}.*degenerate_face.obj: face 1: degenerate, repeats a vertex \\(3 3 5\\)" step ${BAD}/degenerate_face.obj ${BAD}/degenerate_face.obj)
cli_test(bad.obj_duplicate_face 2 "${E}.*duplicate_face.obj: face 2: duplicate of face 1" step ${BAD}/duplicate_face.obj ${BAD}/duplicate_face.obj)
cli_test(bad.obj_two_vertex_face 2 "${E}.*two_vertex_face.obj:8: face: face has 2 vertices, expected at least 3" step ${T0} ${BAD}/two_vertex_face.obj)
cli_test(bad.obj_bad_number 2 "${E}.*bad_number.obj:4: y: expected a number, got 'zero'" step ${T0} ${BAD}/bad_number.obj)
cli_test(bad.obj_too_few_coordinates 2 "${E}.*too_few_coordinates.obj:2: vertex: expected 3 coordinates, got 2" step ${T0} ${BAD}/too_few_coordinates.obj)
cli_test(bad.obj_unknown_record 2 "${E}.*unknown_record.obj:9: unknown OBJ record 'xyz'" step ${T0} ${BAD}/unknown_record.obj)
cli_test(bad.obj_random_bytes 2 "${E}.*random_bytes.obj:1: unknown OBJ record '[^']*\\\\x" step ${T0} ${BAD}/random_bytes.obj)
cli_test(bad.obj_huge_line 2 "${E}.*huge_line.obj:9: vertex 6: non-finite coordinate \\(inf 0 0\\)" step ${T0} ${BAD}/huge_line.obj)
cli_test(bad.obj_other_vertex_count 2 "${E}.*t1_other_vertex_count.obj: 7 vertices, expected 6 as in .*fall_t0.obj" step ${T0} ${BAD}/t1_other_vertex_count.obj)
cli_test(bad.obj_directory 2 "${E}.*bad_inputs: cannot open file \\(it is a directory, expected a file\\)" step ${BAD} ${BAD})
cli_test(ok.obj_non_manifold 0 "contacts vf=1 ee=2" step ${BAD}/non_manifold.obj ${BAD}/non_manifold.obj)
cli_test(ok.obj_crlf 0 "contacts vf=3 ee=0" step ${BAD}/crlf.obj ${CLI_DIR}/fall_t1.obj)
cli_test(ok.obj_bom 0 "contacts vf=3 ee=0" step ${BAD}/bom.obj ${CLI_DIR}/fall_t1.obj)

# PLY
cli_test(bad.ply_empty 2 "${E}.*empty.ply: empty file" step ${T0} ${BAD}/empty.ply)
cli_test(bad.ply_not_ply 2 "${E}.*not_ply.ply:1: not a PLY file \\(first line must be 'ply', got 'PLY\\?'\\)" step ${BAD}/not_ply.ply ${BAD}/not_ply.ply)
cli_test(bad.ply_no_end_header 2 "${E}.*no_end_header.ply:8: header truncated \\(no end_header\\)" step ${BAD}/no_end_header.ply ${BAD}/no_end_header.ply)
cli_test(bad.ply_absurd_vertex_count 2 "${E}.*absurd_vertex_count.ply: element vertex 4000000000000: the header declares more items than the file can hold" step ${BAD}/absurd_vertex_count.ply ${BAD}/absurd_vertex_count.ply)
cli_test(bad.ply_absurd_face_count 2 "${E}.*absurd_face_count.ply: element face 1152921504606846976: the header declares more items than the file can hold" step ${BAD}/absurd_face_count.ply ${BAD}/absurd_face_count.ply)
cli_test(bad.ply_absurd_list_count 2 "${E}.*absurd_list_count.ply: element face 1: list vertex_indices: expected a count from 0 to the file size, got 1000000000000" step ${BAD}/absurd_list_count.ply ${BAD}/absurd_list_count.ply)
cli_test(bad.ply_wrong_vertex_count 2 "${E}.*wrong_vertex_count.ply:17: element face 0: face has 2 vertices, expected at least 3" step ${BAD}/wrong_vertex_count.ply ${BAD}/wrong_vertex_count.ply)
cli_test(bad.ply_truncated_binary 2 "${E}.*truncated_binary.ply: element face 1: file truncated" step ${BAD}/truncated_binary.ply ${BAD}/truncated_binary.ply)
cli_test(bad.ply_garbage_after_body 2 "${E}.*garbage_after_body.ply: 64 unexpected bytes after the last element" step ${BAD}/garbage_after_body.ply ${BAD}/garbage_after_body.ply)
cli_test(bad.ply_garbage_body 2 "${E}.*garbage_body.ply: element" step ${BAD}/garbage_body.ply ${BAD}/garbage_body.ply)
cli_test(bad.ply_nan 2 "${E}.*nan.ply:11: element vertex 1: non-finite coordinate \\(1 nan 0\\)" step ${BAD}/nan.ply ${BAD}/nan.ply)
cli_test(bad.ply_negative_index 2 "${E}.*negative_index.ply:17: element face 1: vertex index -4 out of range \\[0, 6\\)" step ${BAD}/negative_index.ply ${BAD}/negative_index.ply)
cli_test(bad.ply_index_out_of_range 2 "${E}.*index_out_of_range.ply:17: element face 1: vertex index 6 out of range \\[0, 6\\)" step ${BAD}/index_out_of_range.ply ${BAD}/index_out_of_range.ply)
cli_test(bad.ply_float_index 2 "${E}.*float_index.ply: element face 1: vertex index: expected an integer, got 4.5" step ${BAD}/float_index.ply ${BAD}/float_index.ply)
cli_test(bad.ply_bad_property_type 2 "${E}.*bad_property_type.ply:4: property type: expected one of .*, got 'quad'" step ${BAD}/bad_property_type.ply ${BAD}/bad_property_type.ply)
cli_test(bad.ply_unknown_keyword 2 "${E}.*unknown_keyword.ply:3: unknown header keyword 'frobnicate'" step ${BAD}/unknown_keyword.ply ${BAD}/unknown_keyword.ply)
cli_test(ok.ply_crlf 0 "contacts vf=0 ee=0" step ${BAD}/crlf.ply ${BAD}/crlf.ply)
cli_test(ok.ply_bom 0 "contacts vf=0 ee=0" step ${BAD}/bom.ply ${BAD}/crlf.ply)

# YAML configs and frame sequences
cli_test(bad.yaml_empty 2 "${E}.*empty.yaml: scene: required key missing" run ${BAD}/empty.yaml)
cli_test(bad.yaml_list 2 "${E}.*list.yaml:1: expected a mapping of config keys .*, got a list" run ${BAD}/list.yaml)
cli_test(bad.yaml_binary 2 "${E}.*binary.yaml:1: expected a mapping of config keys" run ${BAD}/binary.yaml --set output.dir=out)
cli_test(bad.yaml_syntax 2 "${E}.*syntax_error.yaml:3: YAML syntax error" run ${BAD}/syntax_error.yaml)
cli_test(bad.yaml_threads_zero 2 "${E}.*threads_zero.yaml:3: threads: expected an integer from 1 to 1024, got '0'" run ${BAD}/threads_zero.yaml)
cli_test(bad.yaml_threads_huge 2 "${E}.*threads_huge.yaml:3: threads: expected an integer from 1 to 1024, got '100000'" run ${BAD}/threads_huge.yaml)
cli_test(bad.yaml_key_twice 2 "${E}.*key_twice.yaml:4: threads: given twice \\(first at line 3\\)" run ${BAD}/key_twice.yaml)
cli_test(bad.yaml_nested_key_twice 2 "${E}.*nested_key_twice.yaml:5: scene.resolution: given twice \\(first at line 4\\)" run ${BAD}/nested_key_twice.yaml)
cli_test(bad.set_key_twice 2 "${E}--set threads=2: threads is set twice" run ${CLI_DIR}/tiny.yaml --set threads=1 --set threads=2)
cli_test(bad.yaml_directory 2 "${E}.*bad_inputs: cannot open file \\(it is a directory, expected a file\\)" run ${BAD})
# A bad last frame is found before the first step: no result files are left behind (checked by the regex on
# the absence of the table's summary line).
cli_test(bad.frames_missing_late 2 "^${E}.*missing_frame.obj: cannot open file \\(no such file\\) *$" run ${BAD}/missing_frame.yaml --no-progress --set output.dir=out)
cli_test(bad.frames_nan_late 2 "^${E}.*nan.obj:5: vertex 4: non-finite coordinate \\(0.6 nan 1\\) *$" run ${BAD}/bad_frame_late.yaml --no-progress --set output.dir=out)

# Query CSV and ground-truth JSON
cli_test(bad.csv_columns 2 "${E}.*five_columns.csv:8: expected 6 columns like the first row, got 5" validate ${BAD}/queries/edge-edge/five_columns.csv)
cli_test(bad.csv_truncated 2 "${E}.*truncated.csv: truncated: the last query has 5 of its 8 rows" validate ${BAD}/queries/edge-edge/truncated.csv)
cli_test(bad.csv_not_a_number 2 "${E}.*not_a_number.csv:1: column 5: numerator: expected an integer, got 'zero'" validate ${BAD}/queries/edge-edge/not_a_number.csv)
cli_test(bad.csv_zero_denominator 2 "${E}.*zero_denominator.csv:1: column 1: denominator: expected a non-zero integer, got 0" validate ${BAD}/queries/edge-edge/zero_denominator.csv)
cli_test(bad.csv_bad_truth 2 "${E}.*bad_truth.csv:1: column 7 \\(ground truth\\): expected 0 or 1, got '2'" validate ${BAD}/queries/edge-edge/bad_truth.csv)
cli_test(bad.json_short 2 "${E}.*short_truth_ee_mma_bool.json: 1 answers for the 2 queries of .*short_truth_ee.csv" validate ${BAD}/truthless/queries/short_truth_ee.csv)
cli_test(bad.json_broken 2 "${E}.*broken_json_ee_mma_bool.json: invalid JSON" validate ${BAD}/truthless/queries/broken_json_ee.csv)
cli_test(bad.json_missing 2 "${E}.*no_truth_ee.csv: no ground truth: 6-column queries need .*no_truth_ee_mma_bool.json" validate ${BAD}/truthless/queries/no_truth_ee.csv)
cli_test(bad.queries_missing 2 "${E}nowhere: no such file or directory" validate nowhere)

# Command-line mistakes
cli_test(bad.cli_unknown_command 2 "${E}unknown command 'frobnicate', expected one of run, sweep, step, proximity, bench, simulate, export, validate, list, info" frobnicate)
cli_test(bad.cli_no_command 2 "${E}A subcommand is required" )
cli_test(bad.cli_unknown_flag 2 "${E}The following argument was not expected: --bogus \\(ccdlab step --help\\)" step ${T0} ${T0} --bogus)
cli_test(bad.cli_missing_argument 2 "${E}t1 is required" step ${T0})
cli_test(bad.cli_k_not_a_number 2 "${E}--k: expected an integer, got 'abc'" step ${T0} ${T0} --k abc)
cli_test(bad.cli_k_out_of_range 2 "${E}--k: expected one of 6, 14, 18, 26, got 99999999999999" step ${T0} ${T0} --k 99999999999999)
cli_test(bad.cli_tester_key_twice 2 "${E}--tester float:thickness=1e-4,thickness=2e-4: 'thickness' is given twice" step ${T0} ${T0} --tester float:thickness=1e-4,thickness=2e-4)
cli_test(bad.cli_threads_huge 2 "${E}--threads: expected an integer from 1 to 1024, got 100000" step ${T0} ${T0} --threads 100000)
cli_test(bad.cli_threads_zero 2 "${E}--threads: expected an integer from 1 to 1024, got 0" step ${T0} ${T0} --threads 0)
cli_test(bad.cli_bench_threads_huge 2 "${E}--threads: expected a comma-separated list of integers from 1 to 1024, got '1,100000'" bench ${CLI_DIR}/tiny.yaml --threads 1,100000)
cli_test(bad.cli_bench_rounds 2 "${E}--rounds: expected an integer >= 1, got 0" bench ${CLI_DIR}/tiny.yaml --rounds 0)
cli_test(bad.cli_validate_repeat 2 "${E}--repeat: expected an integer from 1 to 1000000, got 0" validate hard-cases --repeat 0)
cli_test(bad.cli_validate_failures 2 "${E}--failures: expected an integer >= 0, got -1" validate hard-cases --failures -1)
cli_test(bad.out_contacts_no_dir 2 "${E}--contacts: cannot write '/nonexistent/dir/c.csv' \\(No such file or directory\\)" step ${T0} ${CLI_DIR}/fall_t1.obj --contacts /nonexistent/dir/c.csv)
cli_test(bad.out_contacts_directory 2 "${E}--contacts: cannot write '.' \\(it is a directory\\)" step ${T0} ${CLI_DIR}/fall_t1.obj --contacts .)
cli_test(bad.out_dir_is_file 2 "${E}output.dir: cannot create '.*fall_t0.obj': a file of that name exists" run ${CLI_DIR}/tiny.yaml --set output.dir=${T0})
cli_test(ok.version 0 "^ccdlab [0-9a-f]+" --version)

# Memory: a generated scene too large for memory_limit is refused before it is made; a run whose structures
# would not fit is refused before its first step; a bad size is named.
cli_test(bad.memory_scene_too_large 2 "${E}memory_limit 1.00 GiB: scene drape_fold would have 32000064 triangles, which need at least" run ${CLI_DIR}/tiny.yaml --set scene.resolution=4000 --set memory_limit=1GiB)
cli_test(bad.memory_run_too_large 2 "${E}memory_limit 1.0 MiB: this run needs about .* before its first step" run ${CLI_DIR}/tiny.yaml --set memory_limit=1MiB --set output.dir=out)
cli_test(bad.memory_limit_value 2 "${E}--set memory_limit: memory_limit: expected a size like 8GiB, 512MiB or 60%" run ${CLI_DIR}/tiny.yaml --set memory_limit=lots)
cli_test(bad.memory_limit_flag 2 "${E}--memory-limit: expected a size like 8GiB, 512MiB or 60%" step ${T0} ${T0} --memory-limit 2X)
# Work: a step estimated to explode (a thickness in the wrong unit) is refused before its traversal, naming the
# estimate, the limit and the thickness against the scene; no result is left behind as complete.
cli_test(bad.work_thickness_run 2 "^ccdlab run tiny.*${E}step: about .* candidate triangle pairs expected .*above candidate_limit = 10 per triangle: the tester's thickness 10 is .* the scene's diagonal" run ${CLI_DIR}/tiny.yaml --no-progress --set tester.thickness=10 --set candidate_limit=10 --set output.dir=out_work)
cli_test(bad.work_thickness_step 2 "${E}step: about 1 candidate triangle pairs expected \\(0.5 per triangle of 2.*above candidate_limit = 0.25 per triangle" step ${T0} ${CLI_DIR}/fall_t1.obj --tester float:thickness=10 --candidate-limit 0.25)
cli_test(bad.work_limit_value 2 "${E}--candidate-limit: expected 0 \\(no limit\\) or a finite number > 0, got -1" step ${T0} ${T0} --candidate-limit -1)
# Time: a step past time_limit stops, exit 2, saying where it was and how far it got; no result is left as complete.
cli_test(bad.time_limit_step 2 "${E}time_limit 1e-09 s: the step was stopped after .* candidate pairs tested of about .* expected" step ${T0} ${CLI_DIR}/fall_t1.obj --time-limit 1e-9)
cli_test(bad.time_limit_run 2 "^ccdlab run tiny.*${E}time_limit 1e-09 s: the step was stopped" run ${CLI_DIR}/tiny.yaml --no-progress --set time_limit=1e-9 --set output.dir=out_time)
cli_test(bad.time_limit_value 2 "${E}--time-limit: expected 0 \\(no limit\\) or a finite number of seconds > 0, got -2" step ${T0} ${T0} --time-limit -2)
cli_test(ok.time_limit_step 0 "contacts vf=3 ee=0" step ${T0} ${CLI_DIR}/fall_t1.obj --time-limit 600 --no-progress)
cli_test(ok.memory_limit_step 0 "contacts vf=3 ee=0" step ${T0} ${CLI_DIR}/fall_t1.obj --memory-limit 64MiB)
