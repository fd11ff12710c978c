//! Hot loops built for AVX2 where the processor has it.

/// Defines a function whose body runs as code built for AVX2 (3-operand instructions,
/// packed lanes where a loop allows them) when the processor has AVX2, else as built for
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
                if std::is_x86_feature_detected!("avx2") {
                    // SAFETY: the processor has AVX2 (just checked)
                    return unsafe { avx2 $(::<$($g),*>)? ($($arg),*) };
                }
            }
            body $(::<$($g),*>)? ($($arg),*)
        }
    };
}

pub(crate) use avx2_fn;
