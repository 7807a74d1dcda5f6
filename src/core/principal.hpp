// Principal values and directions of symmetric tensors (Voigt storage, tensor shears), for the
// models that work along principal axes (smeared cracks, fragmentation damage).
#pragma once

namespace shard {

/// The symmetric tensor (Voigt storage) with principal values `value` along the unit `vector`s.
void from_principal(const double value[3], const double vector[3][3], double* t);

/// Eigenvalues (descending) and unit eigenvectors (rows) of a symmetric tensor in Voigt storage.
/// In-plane closed form when the yz and zx components vanish (every 2D point), cyclic Jacobi
/// otherwise.
void principal(const double* t, double value[3], double vector[3][3]);

/// The largest eigenvalue of a symmetric tensor (closed form: in-plane, or the trigonometric
/// solution of the characteristic cubic, Smith 1961).
double major_principal(const double* t);

}  // namespace shard
