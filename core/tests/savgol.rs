//! Savitzky-Golay (method.md section 2.4) against exact rational least
//! squares: the centre kernels, exactness on cubics, and the edge windows.

mod common;

use common::{close, max_abs};
use dmpscope_core::prepare::savgol::SavGol;
use dmpscope_core::rng::Rng;

/// An exact fraction `n / d` (`d > 0`, lowest terms).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Q(i128, i128);

fn gcd(a: i128, b: i128) -> i128 {
    if b == 0 { a.abs() } else { gcd(b, a % b) }
}

impl Q {
    fn new(n: i128, d: i128) -> Self {
        assert!(d != 0, "zero denominator");
        let g = gcd(n, d).max(1) * d.signum();
        Q(n / g, d / g)
    }
    fn int(n: i128) -> Self {
        Q(n, 1)
    }
    fn f64(self) -> f64 {
        self.0 as f64 / self.1 as f64
    }
}

impl std::ops::Add for Q {
    type Output = Q;
    fn add(self, o: Q) -> Q {
        Q::new(self.0 * o.1 + o.0 * self.1, self.1 * o.1)
    }
}

impl std::ops::Mul for Q {
    type Output = Q;
    fn mul(self, o: Q) -> Q {
        Q::new(self.0 * o.0, self.1 * o.1)
    }
}

const HALF: i128 = 10; // window 21 = 2 * HALF + 1

/// Exact cubic least-squares weights on the window `j = -10..=10`:
/// `a[q][j + 10]` is the weight of sample `j` in the coefficient of `t^q`.
/// The even part {1, t^2} and the odd part {t, t^3} decouple on a symmetric
/// window, so each is a 2x2 normal system solved by Cramer's rule.
fn exact_lsq() -> [[Q; 21]; 4] {
    let sum = |p: u32| (-HALF..=HALF).map(|j| j.pow(p)).sum::<i128>();
    let (s0, s2, s4, s6) = (sum(0), sum(2), sum(4), sum(6));
    let det_even = s0 * s4 - s2 * s2;
    let det_odd = s2 * s6 - s4 * s4;
    let mut a = [[Q::int(0); 21]; 4];
    for j in -HALF..=HALF {
        let i = (j + HALF) as usize;
        a[0][i] = Q::new(s4 - s2 * j * j, det_even);
        a[2][i] = Q::new(s0 * j * j - s2, det_even);
        a[1][i] = Q::new(s6 * j - s4 * j * j * j, det_odd);
        a[3][i] = Q::new(s2 * j * j * j - s4 * j, det_odd);
    }
    a
}

/// Exact weights of derivative `deriv` of the window's fit at offset `u`
/// (unit spacing).
fn exact_kernel(a: &[[Q; 21]; 4], deriv: usize, u: i128) -> Vec<Q> {
    let u = Q::int(u);
    (0..21)
        .map(|i| match deriv {
            0 => a[0][i] + a[1][i] * u + a[2][i] * u * u + a[3][i] * u * u * u,
            1 => a[1][i] + Q::int(2) * a[2][i] * u + Q::int(3) * a[3][i] * u * u,
            _ => Q::int(2) * a[2][i] + Q::int(6) * a[3][i] * u,
        })
        .collect()
}

// ---------------------------------------------------------- Savitzky-Golay

#[test]
fn savgol_centre_kernels_equal_exact_least_squares() {
    let a = exact_lsq();
    // The classic closed form of the smoothing weights, m = 10.
    let m = HALF;
    let den = (2 * m + 1) * (4 * m * m + 4 * m - 3);
    for j in -m..=m {
        let classic = Q::new(3 * (3 * m * m + 3 * m - 1) - 15 * j * j, den);
        assert_eq!(a[0][(j + m) as usize], classic, "j = {j}");
    }
    let (centre, end) = (Q::new(329, 3059), Q::new(-171, 3059));
    assert_eq!((a[0][0], a[0][10], a[0][20]), (end, centre, end));
    // The exact kernels differentiate: d/dt t = 1, d2/dt2 t^2 = 2.
    let moment = |k: Vec<Q>, p| {
        (-HALF..=HALF)
            .zip(k)
            .fold(Q::int(0), |s, (j, w)| s + w * Q::int(j.pow(p)))
    };
    assert_eq!(moment(exact_kernel(&a, 1, 0), 1), Q::int(1));
    assert_eq!(moment(exact_kernel(&a, 2, 0), 2), Q::int(2));

    let sg = SavGol::new(21, 3).expect("savgol");
    for deriv in 0..3 {
        let ours = sg.centre_kernel(deriv);
        assert_eq!(ours.len(), 21);
        for (i, e) in exact_kernel(&a, deriv, 0).iter().enumerate() {
            close(ours[i], e.f64(), 1e-13, format_args!("d{deriv} {e:?}"));
        }
    }
}

#[test]
fn savgol_reproduces_cubics_exactly_with_non_unit_spacing() {
    let sg = SavGol::new(21, 3).expect("savgol");
    let (h, n) = (0.037, 40);
    let t: Vec<f64> = (0..n).map(|k| k as f64 * h - 0.6).collect();
    let p: Vec<f64> = t
        .iter()
        .map(|t| 0.3 - 1.2 * t + 2.5 * t * t - 0.7 * t.powi(3))
        .collect();
    let dp: Vec<f64> = t.iter().map(|t| -1.2 + 5.0 * t - 2.1 * t * t).collect();
    let ddp: Vec<f64> = t.iter().map(|t| 5.0 - 4.2 * t).collect();
    let out = sg.apply(&p, h).expect("apply");
    for (name, ours, exact) in [
        ("y", &out.value, &p),
        ("d1", &out.d1, &dp),
        ("d2", &out.d2, &ddp),
    ] {
        let tol = 1e-10 * max_abs(exact.iter().copied());
        for k in 0..n {
            close(ours[k], exact[k], tol, format_args!("{name}[{k}]"));
        }
    }
}

#[test]
fn savgol_equals_window_least_squares_everywhere_including_edges() {
    let sg = SavGol::new(21, 3).expect("savgol");
    let a = exact_lsq();
    let (h, n) = (0.0125_f64, 50usize);
    let mut rng = Rng::new(42);
    let signal: Vec<f64> = (0..n)
        .map(|k| (k as f64 * 0.2).sin() + 0.05 * rng.normal())
        .collect();
    let out = sg.apply(&signal, h).expect("apply");
    for k in 0..n {
        // The window holding k: the first or last 21 samples at the edges.
        let start = k.saturating_sub(10).min(n - 21);
        let u = k as i128 - start as i128 - HALF;
        for (deriv, ours) in [&out.value, &out.d1, &out.d2].into_iter().enumerate() {
            let terms: Vec<f64> = exact_kernel(&a, deriv, u)
                .iter()
                .zip(&signal[start..start + 21])
                .map(|(w, y)| w.f64() * y / h.powi(deriv as i32))
                .collect();
            let tol = 1e-13 * terms.iter().map(|t| t.abs()).sum::<f64>();
            let what = format_args!("derivative {deriv} at sample {k} (offset {u})");
            close(ours[k], terms.iter().sum(), tol, what);
        }
    }
}
