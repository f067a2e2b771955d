# Robot description front end: load_robot unit tests, geometry of the shipped robots, and the
# broken-file corpus run through `dyncc check`.
dyncc_add_test(robot_tests
  ${CMAKE_CURRENT_LIST_DIR}/robot_load_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/robot_geometry_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/robot_corpus_test.cpp
)
# The corpus tests run the dyncc executable.
add_dependencies(robot_tests dyncc)
