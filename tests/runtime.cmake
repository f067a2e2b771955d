# The adaptive-control runtime (runtime/) in closed loop on a hand-written pendulum and on the
# generated Kraft model. Included by tests/CMakeLists.txt, so paths are relative to tests/.
dyncc_add_test(runtime_tests runtime_controller_test.cpp)
target_link_libraries(runtime_tests PRIVATE dyncc_runtime dyncc_generated_kraft_right)
# The controller path as firmware compiles it (float, -fno-exceptions -fno-rtti, -Werror).
add_library(runtime_freestanding_check OBJECT runtime_freestanding_check.cpp)
target_link_libraries(runtime_freestanding_check PRIVATE dyncc_runtime dyncc_generated_kraft_right)
target_compile_options(runtime_freestanding_check PRIVATE -Wall -Wextra -Wpedantic -Werror -Wconversion -fno-exceptions -fno-rtti)
add_dependencies(runtime_tests runtime_freestanding_check)
