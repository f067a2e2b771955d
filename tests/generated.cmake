# The checked-in generated models (generated/<robot>/) against the derivation and `dyncc eval`.
# Included by tests/CMakeLists.txt, so paths are relative to tests/.
dyncc_add_test(generated_model_tests generated_model_test.cpp)
target_link_libraries(generated_model_tests PRIVATE dyncc_pipeline nlohmann_json::nlohmann_json
  dyncc_generated_kraft_right dyncc_generated_planar_2link dyncc_generated_puma560 dyncc_generated_panda)
add_dependencies(generated_model_tests dyncc)
