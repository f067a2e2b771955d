// ARM semihosting: the firmware's only I/O, through the debugger (here QEMU) by `bkpt 0xab`.
// Why semihosting and not a UART driver: the output is for the test that compares it with the
// host build, and semihosting also lets the firmware end QEMU with an exit status.
#pragma once

namespace dyncc::firmware {

/// Writes a NUL-terminated string to the host's console (SYS_WRITE0).
void write(const char* text);
/// Ends the program: QEMU exits with status 0 when success, 1 otherwise (SYS_EXIT).
[[noreturn]] void exit(bool success);

}  // namespace dyncc::firmware
