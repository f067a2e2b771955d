# The tele-operation simulation (sim/): the two plants against each other and against closed
# forms, and the paper's findings as comparisons between simulated runs.
dyncc_add_test(sim_plant_tests sim_rigid_plant_test.cpp sim_mujoco_plant_test.cpp)
target_link_libraries(sim_plant_tests PRIVATE dyncc_sim dyncc_mujoco)
target_compile_definitions(sim_plant_tests PRIVATE DYNCC_KRAFT_MJCF="${CMAKE_BINARY_DIR}/kraft.xml")
add_dependencies(sim_plant_tests dyncc_sim_mjcf)
dyncc_add_test(sim_paper_tests sim_paper_test.cpp)
target_link_libraries(sim_paper_tests PRIVATE dyncc_sim)
target_compile_definitions(sim_paper_tests PRIVATE DYNCC_KRAFT_MJCF="${CMAKE_BINARY_DIR}/kraft.xml")
add_dependencies(sim_paper_tests dyncc_sim_mjcf)
dyncc_add_test(sim_cli_tests sim_cli_test.cpp)
add_dependencies(sim_cli_tests dyncc-sim dyncc_sim_mjcf)
# Excitation logs with hidden effects (dyncc-sim excite): the effects file, the physics of each
# effect on both plants, the command line.
dyncc_add_test(sim_excite_tests sim_excite_test.cpp sim_effects_file_test.cpp)
target_link_libraries(sim_excite_tests PRIVATE dyncc_sim)
target_compile_definitions(sim_excite_tests PRIVATE DYNCC_KRAFT_MJCF="${CMAKE_BINARY_DIR}/kraft.xml")
add_dependencies(sim_excite_tests dyncc_sim_mjcf)
dyncc_add_test(sim_excite_cli_tests sim_excite_cli_test.cpp)
add_dependencies(sim_excite_cli_tests dyncc-sim dyncc_sim_mjcf)
