//! Hot loops built for AVX2 where the processor has it.

/// Whether the hot loops run their AVX2 builds: the processor has AVX2 and the
/// environment does not set `GENDPDE_NO_AVX2` (which runs the baseline builds, to check
/// that both give the same bits, as tests/it/guarantees/guarantees.rs does). Decided once per process.
pub fn avx2() -> bool {
    static AVX2: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *AVX2.get_or_init(|| {
        #[cfg(target_arch = "x86_64")]
        let has = std::is_x86_feature_detected!("avx2");
        #[cfg(not(target_arch = "x86_64"))]
        let has = false;
        has && std::env::var_os("GENDPDE_NO_AVX2").is_none()
    })
}

/// Defines a function whose body runs as code built for AVX2 (3-operand instructions,
/// packed lanes where a loop allows them) where [`avx2`] says so, else as built for
/// the baseline. Both run the same IEEE operations in the same order (Rust never fuses or
/// reorders floating-point operations by itself), so they give the same bits. The body is
/// one `#[inline(always)]` function compiled into both; code it calls is compiled into
/// the AVX2 version only where it is inlined.
macro_rules! avx2_fn {
    (
        $(#[$meta:meta])*
        $vis:vis fn $name:ident $(<$($g:ident: $bound:path),*>)? ($($arg:ident: $ty:ty),* $(,)?) $(-> $ret:ty)? $body:block
    ) => {
        $(#[$meta])*
        $vis fn $name $(<$($g: $bound),*>)? ($($arg: $ty),*) $(-> $ret)? {
            #[inline(always)]
            fn body $(<$($g: $bound),*>)? ($($arg: $ty),*) $(-> $ret)? $body
            #[cfg(target_arch = "x86_64")]
            {
                #[target_feature(enable = "avx2")]
                fn avx2 $(<$($g: $bound),*>)? ($($arg: $ty),*) $(-> $ret)? {
                    body $(::<$($g),*>)? ($($arg),*)
                }
                if $crate::simd::avx2() {
                    // SAFETY: the processor has AVX2 (checked by `avx2`)
                    return unsafe { avx2 $(::<$($g),*>)? ($($arg),*) };
                }
            }
            body $(::<$($g),*>)? ($($arg),*)
        }
    };
}

pub(crate) use avx2_fn;
