# Derived dynamics (gen/kinematics, gen/dynamics, gen/base, gen/pipeline) checked against
# independent re-derivations: a numeric recursive Newton-Euler (newton_euler.hpp), the planar
# arm's textbook closed form, the Kraft paper's appendix, exact base-parameter identities, the
# skew-symmetry proof on deliberately wrong C, and `dyncc verify` on every shipped robot.
# Included by tests/CMakeLists.txt, so paths are relative to tests/.
dyncc_add_test(dynamics_tests
  dynamics_newton_euler_test.cpp
  dynamics_newton_euler_symbolic_test.cpp
  dynamics_planar_test.cpp
  dynamics_kraft_test.cpp
  dynamics_base_test.cpp
  dynamics_skew_test.cpp
  dynamics_verify_test.cpp
  dynamics_numeric_batch_test.cpp
)
target_link_libraries(dynamics_tests PRIVATE dyncc_pipeline nlohmann_json::nlohmann_json)
# The verify tests run the dyncc binary (DYNCC_BINARY): build it before the tests.
add_dependencies(dynamics_tests dyncc)
