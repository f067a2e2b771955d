// Firmware entry: runs the shared control loop in float and prints every output through
// semihosting as "label index value", the value as the hexadecimal bits of the float (exact,
// and no printf: nothing that could pull in the heap).
#include <cstdint>
#include <cstring>

#include "control_loop.hpp"
#include "semihosting.hpp"

namespace {

char* append_text(char* out, const char* text) {
  while (*text != '\0') *out++ = *text++;
  return out;
}

char* append_unsigned(char* out, unsigned value) {
  char digits[12];
  int count = 0;
  do {
    digits[count++] = static_cast<char>('0' + value % 10);
    value /= 10;
  } while (value != 0);
  while (count > 0) *out++ = digits[--count];
  return out;
}

char* append_hex(char* out, std::uint32_t bits) {
  constexpr char kHex[] = "0123456789abcdef";
  *out++ = '0';
  *out++ = 'x';
  for (int shift = 28; shift >= 0; shift -= 4) *out++ = kHex[(bits >> static_cast<unsigned>(shift)) & 0xFu];
  return out;
}

}  // namespace

int main() {
  dyncc::firmware::run_control_loop<float>([](const char* label, int index, float value) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    char line[48];
    char* p = append_text(line, label);
    *p++ = ' ';
    p = append_unsigned(p, static_cast<unsigned>(index));
    *p++ = ' ';
    p = append_hex(p, bits);
    *p++ = '\n';
    *p = '\0';
    dyncc::firmware::write(line);
  });
  dyncc::firmware::write("done\n");
  return 0;
}
