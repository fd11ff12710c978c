//! Regularised incomplete gamma function, Gamma-distribution bins and Pearson's
//! chi-square goodness-of-fit test (Numerical Recipes 6.2 and 14.3).

/// ln Gamma(x) by the Lanczos approximation (|error| < 2e-10).
pub fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 6] = [76.18009172947146, -86.50532032941677, 24.01409824083091, -1.231739572450155, 0.1208650973866179e-2, -0.5395239384953e-5];
    let tmp = x + 5.5 - (x + 0.5) * (x + 5.5).ln();
    let mut ser = 1.000000000190015;
    for (k, c) in C.iter().enumerate() {
        ser += c / (x + 1.0 + k as f64);
    }
    -tmp + (2.5066282746310005 * ser / x).ln()
}

/// P(a, x), the regularised lower incomplete gamma function.
pub fn gamma_p(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    let gln = ln_gamma(a);
    if x < a + 1.0 {
        let (mut ap, mut sum) = (a, 1.0 / a);
        let mut del = sum;
        for _ in 0..10_000 {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if del.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        sum * (-x + a * x.ln() - gln).exp()
    } else {
        // continued fraction for Q (modified Lentz)
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-15 {
                break;
            }
        }
        1.0 - (-x + a * x.ln() - gln).exp() * h
    }
}

/// CDF of Gamma(shape k, scale s).
pub fn gamma_cdf(x: f64, k: f64, s: f64) -> f64 {
    gamma_p(k, x / s)
}

/// Bin edges splitting Gamma(k, s) into `bins` equiprobable intervals (inner edges).
pub fn gamma_quantile_edges(k: f64, s: f64, bins: usize) -> Vec<f64> {
    (1..bins)
        .map(|b| {
            let target = b as f64 / bins as f64;
            let (mut lo, mut hi) = (0.0, k * s * 10.0 + 100.0 * s);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if gamma_cdf(mid, k, s) < target { lo = mid } else { hi = mid }
            }
            0.5 * (lo + hi)
        })
        .collect()
}

/// Pearson's chi-square of `samples` against equiprobable bins with inner `edges`;
/// returns (chi2, degrees of freedom, p-value).
pub fn chi_square_equiprobable(samples: &[f64], edges: &[f64]) -> (f64, usize, f64) {
    let bins = edges.len() + 1;
    let mut counts = vec![0usize; bins];
    for &x in samples {
        counts[edges.partition_point(|&e| e <= x)] += 1;
    }
    let expect = samples.len() as f64 / bins as f64;
    let chi2: f64 = counts.iter().map(|&c| (c as f64 - expect).powi(2) / expect).sum();
    let dof = bins - 1;
    (chi2, dof, 1.0 - gamma_p(dof as f64 / 2.0, chi2 / 2.0))
}

pub fn mean(x: &[f64]) -> f64 {
    x.iter().sum::<f64>() / x.len() as f64
}

pub fn variance(x: &[f64]) -> f64 {
    let m = mean(x);
    x.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / (x.len() - 1) as f64
}

