# dyncc export (gen/export): the MJCF of every shipped robot loaded into MuJoCo and compared with
# dyncc's dynamics; the URDF parsed (tinyxml2) and evaluated with the plain Eigen rigid-body
# algorithms of bench/; bad input through the command. Included by tests/CMakeLists.txt.
include(${PROJECT_SOURCE_DIR}/bench/baselines.cmake)
find_package(tinyxml2 REQUIRED)
dyncc_add_test(export_tests
  ${CMAKE_CURRENT_LIST_DIR}/export_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/export_urdf_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/export_cli_test.cpp
)
target_link_libraries(export_tests PRIVATE dyncc_pipeline dyncc_baselines tinyxml2::tinyxml2)
# The tests run the dyncc executable.
add_dependencies(export_tests dyncc)
