#pragma once
// Debian 12's SUNDIALS 6.4 libraries are built without optimisation (their N_Vector and band
// kernels are -O0 code: every operand goes through the stack), and a solve of a long chain spends
// a third of its time in those vector loops. SUNDIALS lets a vector carry its own operations, and
// clones (CVODE's and ARKODE's work vectors) inherit them, so the serial vector's element-wise
// operations are replaced here by the same arithmetic compiled with this project's flags. Each
// keeps the library's case distinctions (x + y where a = b = 1, c (x + y) where a = b, ...), so
// that results are bitwise those of the library.
#include <nvector/nvector_serial.h>

namespace contact::sundials {

// Installs the compiled operations on a serial vector (before any clone is taken).
void use_compiled_vector_ops(N_Vector v);

}  // namespace contact::sundials
