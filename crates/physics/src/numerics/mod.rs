//! Small numerical building blocks shared by the physics modules.

pub mod banded;
pub mod budget;
pub mod extrapolation;
pub mod fit;
pub mod gmres;
pub mod quad;
pub mod roots;
pub mod toeplitz;

/// Defines `fn $name(args) -> ret` running `$kernel(args)` compiled for AVX2 when the CPU
/// has it (4-wide vectors for the loops inlined into it, instead of the baseline's 2-wide
/// SSE2), else as built. Without FMA the operations and their order are the same, and so
/// are the results, bit for bit (the kind fingerprints check it). For the hot kernels
/// (`fem::element`, `numerics::banded`), whose helpers are `#[inline(always)]` so that they
/// are compiled inside it.
macro_rules! vectorized_fn {
    ($(#[$m:meta])* $vis:vis fn $name:ident($($arg:ident: $ty:ty),*) -> $ret:ty = $kernel:path;) => {
        $(#[$m])*
        $vis fn $name($($arg: $ty),*) -> $ret {
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx2") {
                #[target_feature(enable = "avx2")]
                fn avx2($($arg: $ty),*) -> $ret {
                    $kernel($($arg),*)
                }
                // SAFETY: the CPU has AVX2, checked just above.
                return unsafe { avx2($($arg),*) };
            }
            $kernel($($arg),*)
        }
    };
}
pub(crate) use vectorized_fn;
