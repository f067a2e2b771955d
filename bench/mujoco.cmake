# MuJoCo (Debian libmujoco-dev 2.2.2) as the target dyncc_mujoco, for bench/ and tests/.
# Why not find_package(mujoco): Debian's package config lists /usr/include/libqhull_r/ as an
# include directory, which exists only when libqhull-dev (not a dependency of libmujoco-dev) is
# installed, and CMake refuses a target with a missing include directory. The header and the
# library are all that is needed.
include_guard(GLOBAL)
find_path(MUJOCO_INCLUDE_DIR mujoco/mujoco.h REQUIRED)
find_library(MUJOCO_LIBRARY mujoco REQUIRED)
add_library(dyncc_mujoco INTERFACE)
target_include_directories(dyncc_mujoco SYSTEM INTERFACE ${MUJOCO_INCLUDE_DIR})
target_link_libraries(dyncc_mujoco INTERFACE ${MUJOCO_LIBRARY})
