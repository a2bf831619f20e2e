#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Figures for everyone: the zone colours and the curves' palette stay apart
//! for people with red–green colour blindness.
//!
//! Each colour is seen as a deuteranope and as a protanope would see it, by the simulation of
//! Machado, Oliveira & Fernandes (2009), "A physiologically-based model for simulation of color
//! vision deficiency", IEEE TVCG 15(6) 1291–1298: a 3 × 3 matrix on linear sRGB, the matrices
//! of their Table (severity 1.0, i.e. dichromacy). Two colours are told apart when their
//! CIEDE2000 colour difference is at least 10, computed as in Sharma, Wu & Dalal (2005), "The
//! CIEDE2000 color-difference formula: implementation notes, supplementary test data, and
//! mathematical observations", Color Res. Appl. 30(1) 21–30 (Eqs 1–22), checked here against
//! all 34 of their published test pairs (their Table 1) to 1e-4. sRGB → XYZ (D65) → CIELAB as
//! in IEC 61966-2-1 and CIE 15:2004. Written here rather than taken from a crate: it is about
//! sixty lines, and the test must show which equations it checks.

use thud::export::figures;
use thud::export::svg::PALETTE;

/// CIELAB L*, a*, b*.
type Lab = [f64; 3];

/// CIEDE2000 ΔE00 between two CIELAB colours, kL = kC = kH = 1 (Sharma et al. 2005, Eqs 1–22).
fn delta_e_2000(lab1: Lab, lab2: Lab) -> f64 {
    let ([l1, a1, b1], [l2, a2, b2]) = (lab1, lab2);
    let pow7 = |c: f64| c.powi(7);
    let c_bar = 0.5 * (a1.hypot(b1) + a2.hypot(b2));
    let g = 0.5 * (1.0 - (pow7(c_bar) / (pow7(c_bar) + pow7(25.0))).sqrt()); // Eq 3
    let (a1p, a2p) = ((1.0 + g) * a1, (1.0 + g) * a2); // Eq 4
    let (c1p, c2p) = (a1p.hypot(b1), a2p.hypot(b2)); // Eq 5
    let hue = |a: f64, b: f64| {
        if a == 0.0 && b == 0.0 {
            0.0
        } else {
            b.atan2(a).to_degrees().rem_euclid(360.0)
        }
    }; // Eq 6
    let (h1p, h2p) = (hue(a1p, b1), hue(a2p, b2));
    let dl = l2 - l1; // Eq 8
    let dc = c2p - c1p; // Eq 9
    let dh = if c1p * c2p == 0.0 {
        0.0
    } else if (h2p - h1p).abs() <= 180.0 {
        h2p - h1p
    } else if h2p - h1p > 180.0 {
        h2p - h1p - 360.0
    } else {
        h2p - h1p + 360.0
    }; // Eq 10
    let dh_big = 2.0 * (c1p * c2p).sqrt() * (dh.to_radians() / 2.0).sin(); // Eq 11
    let l_bar = 0.5 * (l1 + l2); // Eq 12
    let c_bar_p = 0.5 * (c1p + c2p); // Eq 13
    let h_bar = if c1p * c2p == 0.0 {
        h1p + h2p
    } else if (h1p - h2p).abs() <= 180.0 {
        0.5 * (h1p + h2p)
    } else if h1p + h2p < 360.0 {
        0.5 * (h1p + h2p + 360.0)
    } else {
        0.5 * (h1p + h2p - 360.0)
    }; // Eq 14
    let cos = |deg: f64| deg.to_radians().cos();
    let t = 1.0 - 0.17 * cos(h_bar - 30.0) + 0.24 * cos(2.0 * h_bar) + 0.32 * cos(3.0 * h_bar + 6.0)
        - 0.20 * cos(4.0 * h_bar - 63.0); // Eq 15
    let d_theta = 30.0 * (-((h_bar - 275.0) / 25.0).powi(2)).exp(); // Eq 16
    let r_c = 2.0 * (pow7(c_bar_p) / (pow7(c_bar_p) + pow7(25.0))).sqrt(); // Eq 17
    let s_l = 1.0 + 0.015 * (l_bar - 50.0).powi(2) / (20.0 + (l_bar - 50.0).powi(2)).sqrt(); // Eq 18
    let s_c = 1.0 + 0.045 * c_bar_p; // Eq 19
    let s_h = 1.0 + 0.015 * c_bar_p * t; // Eq 20
    let r_t = -(2.0 * d_theta).to_radians().sin() * r_c; // Eq 21
    let (x, y, z) = (dl / s_l, dc / s_c, dh_big / s_h);
    (x * x + y * y + z * z + r_t * y * z).sqrt() // Eq 22
}

/// Sharma et al. (2005), Table 1: the 34 test pairs (L*, a*, b*) × 2 and their ΔE00.
const SHARMA_PAIRS: [(Lab, Lab, f64); 34] = [
    ([50.0, 2.6772, -79.7751], [50.0, 0.0, -82.7485], 2.0425),
    ([50.0, 3.1571, -77.2803], [50.0, 0.0, -82.7485], 2.8615),
    ([50.0, 2.8361, -74.0200], [50.0, 0.0, -82.7485], 3.4412),
    ([50.0, -1.3802, -84.2814], [50.0, 0.0, -82.7485], 1.0000),
    ([50.0, -1.1848, -84.8006], [50.0, 0.0, -82.7485], 1.0000),
    ([50.0, -0.9009, -85.5211], [50.0, 0.0, -82.7485], 1.0000),
    ([50.0, 0.0, 0.0], [50.0, -1.0, 2.0], 2.3669),
    ([50.0, -1.0, 2.0], [50.0, 0.0, 0.0], 2.3669),
    ([50.0, 2.4900, -0.0010], [50.0, -2.4900, 0.0009], 7.1792),
    ([50.0, 2.4900, -0.0010], [50.0, -2.4900, 0.0010], 7.1792),
    ([50.0, 2.4900, -0.0010], [50.0, -2.4900, 0.0011], 7.2195),
    ([50.0, 2.4900, -0.0010], [50.0, -2.4900, 0.0012], 7.2195),
    ([50.0, -0.0010, 2.4900], [50.0, 0.0009, -2.4900], 4.8045),
    ([50.0, -0.0010, 2.4900], [50.0, 0.0010, -2.4900], 4.8045),
    ([50.0, -0.0010, 2.4900], [50.0, 0.0011, -2.4900], 4.7461),
    ([50.0, 2.5, 0.0], [50.0, 0.0, -2.5], 4.3065),
    ([50.0, 2.5, 0.0], [73.0, 25.0, -18.0], 27.1492),
    ([50.0, 2.5, 0.0], [61.0, -5.0, 29.0], 22.8977),
    ([50.0, 2.5, 0.0], [56.0, -27.0, -3.0], 31.9030),
    ([50.0, 2.5, 0.0], [58.0, 24.0, 15.0], 19.4535),
    ([50.0, 2.5, 0.0], [50.0, 3.1736, 0.5854], 1.0000),
    ([50.0, 2.5, 0.0], [50.0, 3.2972, 0.0], 1.0000),
    ([50.0, 2.5, 0.0], [50.0, 1.8634, 0.5757], 1.0000),
    ([50.0, 2.5, 0.0], [50.0, 3.2592, 0.3350], 1.0000),
    ([60.2574, -34.0099, 36.2677], [60.4626, -34.1751, 39.4387], 1.2644),
    ([63.0109, -31.0961, -5.8663], [62.8187, -29.7946, -4.0864], 1.2630),
    ([61.2901, 3.7196, -5.3901], [61.4292, 2.2480, -4.9620], 1.8731),
    ([35.0831, -44.1164, 3.7933], [35.0232, -40.0716, 1.5901], 1.8645),
    ([22.7233, 20.0904, -46.6940], [23.0331, 14.9730, -42.5619], 2.0373),
    ([36.4612, 47.8580, 18.3852], [36.2715, 50.5065, 21.2231], 1.4146),
    ([90.8027, -2.0831, 1.4410], [91.1528, -1.6435, 0.0447], 1.4441),
    ([90.9257, -0.5406, -0.9208], [88.6381, -0.8985, -0.7239], 1.5381),
    ([6.7747, -0.2908, -2.4247], [5.8714, -0.0985, -2.2286], 0.6377),
    ([2.0776, 0.0795, -1.1350], [0.9033, -0.0636, -0.5514], 0.9082),
];

/// Machado et al. (2009), severity 1.0: protanopia and deuteranopia, on linear sRGB.
const PROTANOPIA: [[f64; 3]; 3] =
    [[0.152_286, 1.052_583, -0.204_868], [0.114_503, 0.786_281, 0.099_216], [-0.003_882, -0.048_116, 1.051_998]];
const DEUTERANOPIA: [[f64; 3]; 3] =
    [[0.367_322, 0.860_646, -0.227_968], [0.280_085, 0.672_501, 0.047_413], [-0.011_820, 0.042_940, 0.968_881]];
const NORMAL: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// `#rrggbb` → linear sRGB in 0..1 (IEC 61966-2-1's transfer function).
fn linear_rgb(hex: &str) -> [f64; 3] {
    let hex = hex.trim_start_matches('#');
    assert_eq!(hex.len(), 6, "{hex}");
    let channel = |i: usize| {
        let c = f64::from(u8::from_str_radix(&hex[i..i + 2], 16).unwrap()) / 255.0;
        if c <= 0.040_45 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    [channel(0), channel(2), channel(4)]
}

/// Linear sRGB → CIELAB (D65 white).
fn lab(rgb: [f64; 3]) -> Lab {
    let [r, g, b] = rgb;
    let x = 0.412_456_4 * r + 0.357_576_1 * g + 0.180_437_5 * b;
    let y = 0.212_672_9 * r + 0.715_152_2 * g + 0.072_175_0 * b;
    let z = 0.019_333_9 * r + 0.119_192_0 * g + 0.950_304_1 * b;
    let f = |t: f64| {
        let d: f64 = 6.0 / 29.0;
        if t > d.powi(3) {
            t.cbrt()
        } else {
            t / (3.0 * d * d) + 4.0 / 29.0
        }
    };
    let (fx, fy, fz) = (f(x / 0.950_47), f(y), f(z / 1.088_83));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// The colour `hex` as seen through `m` (a Machado matrix), in CIELAB.
fn seen(hex: &str, m: &[[f64; 3]; 3]) -> Lab {
    let c = linear_rgb(hex);
    let row = |i: usize| (m[i][0] * c[0] + m[i][1] * c[1] + m[i][2] * c[2]).clamp(0.0, 1.0);
    lab([row(0), row(1), row(2)])
}

/// The smallest ΔE00 between any two of `colors` for normal vision, a deuteranope and a
/// protanope: (ΔE, vision, colour, colour).
pub fn closest_pair(colors: &[&str]) -> (f64, &'static str, String, String) {
    let mut worst = (f64::INFINITY, "", String::new(), String::new());
    for (name, m) in [("normal vision", &NORMAL), ("deuteranopia", &DEUTERANOPIA), ("protanopia", &PROTANOPIA)] {
        for (i, a) in colors.iter().enumerate() {
            for b in &colors[i + 1..] {
                let d = delta_e_2000(seen(a, m), seen(b, m));
                if d < worst.0 {
                    worst = (d, name, (*a).to_string(), (*b).to_string());
                }
            }
        }
    }
    worst
}

pub const MIN_DELTA_E: f64 = 10.0;

#[test]
fn ciede2000_reproduces_sharma_s_34_test_pairs() {
    for (k, (a, b, want)) in SHARMA_PAIRS.iter().enumerate() {
        let got = delta_e_2000(*a, *b);
        assert!((got - want).abs() < 1e-4, "pair {}: ΔE00 {got:.4}, Sharma et al. {want}", k + 1);
        // ΔE00 is symmetric.
        assert!((delta_e_2000(*b, *a) - got).abs() < 1e-9, "pair {}", k + 1);
    }
}

#[test]
fn the_simulation_merges_what_red_green_blind_people_confuse() {
    // The check can fail: the old zone colours (red, orange, green, blue) of thud 0.1 put zone 1
    // and zone 3 within ΔE 6 for a deuteranope, as the issue saw.
    let old = ["#e8787a", "#f7b267", "#7fc97f", "#8fb8de", "#dddddd"];
    let (d, vision, ..) = closest_pair(&old);
    assert!(d < MIN_DELTA_E, "{d} {vision}");
    let (red, green) = ("#e8787a", "#7fc97f");
    assert!(delta_e_2000(seen(red, &NORMAL), seen(green, &NORMAL)) > 40.0);
    assert!(delta_e_2000(seen(red, &DEUTERANOPIA), seen(green, &DEUTERANOPIA)) < 8.0);
    // The matrices keep white and grey (each row sums to 1).
    for m in [&PROTANOPIA, &DEUTERANOPIA] {
        assert!(delta_e_2000(seen("#808080", m), seen("#808080", &NORMAL)) < 0.1);
    }
}

#[test]
fn zone_colours_stay_apart_for_deuteranopes_and_protanopes() {
    for (what, colors) in [("zone cells", figures::zone_colors()), ("Fig 17's zone points", figures::zone_dot_colors())]
    {
        let (d, vision, a, b) = closest_pair(&colors);
        assert!(d >= MIN_DELTA_E, "{what}: {a} and {b} are ΔE00 {d:.1} apart with {vision}");
    }
}

#[test]
fn the_curves_palette_stays_apart_for_deuteranopes_and_protanopes() {
    // Every multi-curve figure takes its colours from this palette (export::svg::series_color).
    let (d, vision, a, b) = closest_pair(&PALETTE);
    assert!(d >= MIN_DELTA_E, "curves: {a} and {b} are ΔE00 {d:.1} apart with {vision}");
    for (k, color) in PALETTE.iter().enumerate() {
        assert_eq!(thud::export::svg::series_color(k), *color);
    }
}
