// Reset handler and vector table for the Cortex-M4F: copy .data, zero .bss, turn on the FPU
// (the generated code is hard-float), run static constructors, call main, report its result.
#include <cstdint>

#include "semihosting.hpp"

extern "C" {
extern std::uint32_t _data_load, _data_start, _data_end, _bss_start, _bss_end, _stack_top;
extern void (*__init_array_start[])();
extern void (*__init_array_end[])();
int main();
void reset_handler();
void fault_handler();
}

void reset_handler() {
  std::uint32_t* source = &_data_load;
  for (std::uint32_t* d = &_data_start; d < &_data_end;) *d++ = *source++;
  for (std::uint32_t* d = &_bss_start; d < &_bss_end;) *d++ = 0;
  // CPACR: full access to coprocessors 10 and 11 (the FPU), then synchronise.
  volatile std::uint32_t& cpacr = *reinterpret_cast<volatile std::uint32_t*>(0xE000ED88);  // NOLINT
  cpacr = cpacr | (0xFu << 20);
  asm volatile("dsb\n\tisb" ::: "memory");
  for (auto* f = __init_array_start; f < __init_array_end; ++f) (*f)();
  dyncc::firmware::exit(main() == 0);
}

void fault_handler() {
  dyncc::firmware::write("fault\n");
  dyncc::firmware::exit(false);
}

// Initial stack pointer, then the handlers: reset, NMI, hard fault, and the configurable faults.
__attribute__((section(".vectors"), used)) void* const vector_table[] = {
    &_stack_top,
    reinterpret_cast<void*>(reset_handler),  // NOLINT
    reinterpret_cast<void*>(fault_handler),  // NOLINT
    reinterpret_cast<void*>(fault_handler),  // NOLINT
    reinterpret_cast<void*>(fault_handler),  // NOLINT
    reinterpret_cast<void*>(fault_handler),  // NOLINT
    reinterpret_cast<void*>(fault_handler),  // NOLINT
};
