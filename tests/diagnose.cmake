# The sim-to-real diagnosis (gen/diagnose): log reading and its errors, the audit, blind
# checks on synthetic logs with one known effect injected, the payload window, the contact
# search, where the held-out blocks go, the numbers behind the report's figures, and whole logs of the blind bench that a binary once got wrong (BlindBenchCase: Release only).
dyncc_add_test(diagnose_tests diagnose_log_test.cpp diagnose_effect_test.cpp diagnose_cli_test.cpp
               diagnose_report_test.cpp diagnose_blind_case_test.cpp diagnose_transmission_test.cpp
               diagnose_regime_error_test.cpp diagnose_plausibility_test.cpp diagnose_payload_window_test.cpp
               diagnose_contact_search_test.cpp diagnose_crossval_test.cpp diagnose_fold_plan_test.cpp
               diagnose_bench_truth_test.cpp)
target_link_libraries(diagnose_tests PRIVATE dyncc_diagnose dyncc_pipeline nlohmann_json::nlohmann_json)
add_dependencies(diagnose_tests dyncc)  # the command-line tests run it
# Unlike the other tests, several of these run the whole diagnosis in-process, and the linker keeps
# the first instance of each Eigen template it meets: the test files' own. At the sanitizer build's
# -O0 for test code the library then runs Eigen unoptimised, 40-65 times slower than in Release
# (FrictionBesideAGainOfItsJointIsReadInAppliedTorque: 72 s); at -O1, 17 s, for about 35 s more
# of compiling these twelve files.
target_compile_options(diagnose_tests PRIVATE $<$<CONFIG:RelWithDebInfo>:-O1>)
