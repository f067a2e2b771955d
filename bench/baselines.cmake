# The speed-comparison baselines (plain Eigen CRBA/RNEA, MuJoCo on the exported MJCF) as one
# static library, dyncc_baselines: the benchmarks time them and the baseline and export tests check
# them, all against one compiled copy (each test executable compiled eigen_rbd.cpp again before).
# Included by bench/CMakeLists.txt and by tests/, which are built without bench/ too.
include_guard(GLOBAL)
include(${CMAKE_CURRENT_LIST_DIR}/mujoco.cmake)
add_library(dyncc_baselines STATIC
  ${CMAKE_CURRENT_LIST_DIR}/eigen_rbd.cpp
  ${CMAKE_CURRENT_LIST_DIR}/rbd_from_description.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mujoco_baseline.cpp
  ${CMAKE_CURRENT_LIST_DIR}/baselines.cpp)
target_include_directories(dyncc_baselines PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(dyncc_baselines PUBLIC dyncc_export dyncc_robot dyncc_sym Eigen3::Eigen dyncc_mujoco
  PRIVATE dyncc_warnings)
