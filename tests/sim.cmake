# The tele-operation simulation (sim/): plots, the two plants against each other and against
# closed forms, and the paper's findings as comparisons between simulated runs.
find_package(tinyxml2 REQUIRED)
dyncc_add_test(sim_plot_tests sim_plot_test.cpp)
target_link_libraries(sim_plot_tests PRIVATE dyncc_sim PkgConfig::CAIRO tinyxml2::tinyxml2)
dyncc_add_test(sim_plant_tests sim_rigid_plant_test.cpp sim_mujoco_plant_test.cpp)
target_link_libraries(sim_plant_tests PRIVATE dyncc_sim dyncc_mujoco)
target_compile_definitions(sim_plant_tests PRIVATE DYNCC_KRAFT_MJCF="${CMAKE_BINARY_DIR}/kraft.xml")
add_dependencies(sim_plant_tests dyncc_sim_mjcf)
dyncc_add_test(sim_paper_tests sim_paper_test.cpp)
target_link_libraries(sim_paper_tests PRIVATE dyncc_sim)
target_compile_definitions(sim_paper_tests PRIVATE DYNCC_KRAFT_MJCF="${CMAKE_BINARY_DIR}/kraft.xml")
add_dependencies(sim_paper_tests dyncc_sim_mjcf)
