# The speed-comparison baselines of bench/ (plain Eigen CRBA/RNEA, MuJoCo on the exported MJCF)
# against dyncc's model. Their sources are compiled in here, since bench/ is only built with
# DYNCC_BUILD_BENCH. Included by tests/CMakeLists.txt.
include(${PROJECT_SOURCE_DIR}/bench/mujoco.cmake)
dyncc_add_test(baseline_tests
  ${CMAKE_CURRENT_LIST_DIR}/baseline_test.cpp
  ${PROJECT_SOURCE_DIR}/bench/eigen_rbd.cpp
  ${PROJECT_SOURCE_DIR}/bench/rbd_from_description.cpp
  ${PROJECT_SOURCE_DIR}/bench/mujoco_baseline.cpp
)
target_include_directories(baseline_tests PRIVATE ${PROJECT_SOURCE_DIR}/bench)
target_link_libraries(baseline_tests PRIVATE dyncc_pipeline dyncc_export dyncc_mujoco)
