# The expression engine's property tests (gen/sym). Included by tests/CMakeLists.txt, so
# paths are relative to tests/.
dyncc_add_test(sym_tests
  sym_canonical_test.cpp
  sym_diff_test.cpp
  sym_expand_substitute_test.cpp
  sym_gradient_modular_test.cpp
  sym_parse_print_test.cpp
  sym_rational_test.cpp
  sym_zero_test.cpp
  sym_evaluate_test.cpp
  sym_cli_test.cpp
)
# The CLI tests run the dyncc binary (DYNCC_BINARY): build it before the tests.
add_dependencies(sym_tests dyncc)
