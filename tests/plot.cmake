# The figures (plot/): write_figure checked by properties of the PNG and SVG files it writes.
find_package(tinyxml2 REQUIRED)
dyncc_add_test(plot_tests plot_test.cpp)
target_link_libraries(plot_tests PRIVATE dyncc_plot PkgConfig::CAIRO tinyxml2::tinyxml2)
