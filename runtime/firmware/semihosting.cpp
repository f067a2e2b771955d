#include "semihosting.hpp"

namespace dyncc::firmware {
namespace {

constexpr int kWrite0 = 0x04;
constexpr int kExit = 0x18;
constexpr int kApplicationExit = 0x20026;  // ADP_Stopped_ApplicationExit
constexpr int kRunTimeError = 0x20023;     // ADP_Stopped_RunTimeErrorUnknown

int call(int operation, const void* argument) {
  register int r0 asm("r0") = operation;
  register const void* r1 asm("r1") = argument;
  asm volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

}  // namespace

void write(const char* text) { call(kWrite0, text); }

void exit(bool success) {
  // On 32-bit ARM the reason code itself is the argument.
  call(kExit, reinterpret_cast<const void*>(success ? kApplicationExit : kRunTimeError));  // NOLINT
  for (;;) {
  }
}

}  // namespace dyncc::firmware
