# The speed-comparison baselines of bench/ (plain Eigen CRBA/RNEA, MuJoCo on the exported MJCF)
# against dyncc's model. Included by tests/CMakeLists.txt.
include(${PROJECT_SOURCE_DIR}/bench/baselines.cmake)
dyncc_add_test(baseline_tests ${CMAKE_CURRENT_LIST_DIR}/baseline_test.cpp)
target_link_libraries(baseline_tests PRIVATE dyncc_pipeline dyncc_baselines)
