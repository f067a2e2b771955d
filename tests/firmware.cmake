# The Kraft controller as Cortex-M4F firmware under QEMU, compared with this host build in
# double (runtime/firmware/). Skipped (exit 77) where arm-none-eabi or QEMU is missing; CI
# installs both. Included by tests/CMakeLists.txt, so paths are relative to tests/.
add_executable(firmware_reference firmware_reference.cpp)
target_include_directories(firmware_reference PRIVATE ${PROJECT_SOURCE_DIR}/runtime/firmware)
target_link_libraries(firmware_reference PRIVATE dyncc_runtime dyncc_generated_kraft_right dyncc_warnings)
add_test(NAME firmware.QemuMatchesHostDouble
         COMMAND ${PROJECT_SOURCE_DIR}/runtime/firmware/run_qemu_test.sh ${CMAKE_BINARY_DIR}/firmware
                 $<TARGET_FILE:firmware_reference>)
set_tests_properties(firmware.QemuMatchesHostDouble PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600)
