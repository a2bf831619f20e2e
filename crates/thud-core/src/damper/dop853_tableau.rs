//! The Runge–Kutta tableau of DOP853 (Dormand & Prince's explicit pair of order 8 with error
//! estimators of orders 5 and 3 and a dense output of order 7; Hairer, Nørsett & Wanner,
//! *Solving Ordinary Differential Equations I*, 2nd ed., §II.10, and Hairer's `dop853.f`), as
//! straight-line stage sums for [`super::dop853`]: the coefficients are those of SciPy's
//! `dop853_coefficients.py` (a transcription of `dop853.f`), printed as the nearest `f64`, with
//! the zero entries left out so that no stage multiplies by zero. Generated, then the dense-output
//! stages 14 … 16 moved to their own array (`kx`) so that building a step's dense output reads the
//! step's rates in place instead of copying them.
#![allow(clippy::unreadable_literal, clippy::excessive_precision, clippy::too_many_lines)]

// Over 80 lines: the generated stage sums of the tableau, one straight line per stage.
/// The stages 2 … 12 of one step from `y` (`k[0]` holds the rate there): `f(i, state, k_i, kq_i)` writes the rate of stage `i`.
#[inline(always)]
#[allow(clippy::needless_range_loop)]
pub(super) fn stages<const N: usize>(
    y: &[f64; N],
    h: f64,
    k: &mut [[f64; N]; 13],
    kq: &mut [[f64; 3]; 13],
    mut f: impl FnMut(usize, &[f64; N], &mut [f64; N], &mut [f64; 3]),
) {
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = y[m] + h * (0.05260015195876773 * k[0][m]);
    }
    {
        let (kk, qq) = (&mut k[1], &mut kq[1]);
        f(1, &s, kk, qq);
    }
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = y[m] + h * (0.0197250569845379 * k[0][m] + 0.0591751709536137 * k[1][m]);
    }
    {
        let (kk, qq) = (&mut k[2], &mut kq[2]);
        f(2, &s, kk, qq);
    }
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = y[m] + h * (0.02958758547680685 * k[0][m] + 0.08876275643042054 * k[2][m]);
    }
    {
        let (kk, qq) = (&mut k[3], &mut kq[3]);
        f(3, &s, kk, qq);
    }
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = y[m] + h * (0.2413651341592667 * k[0][m] + -0.8845494793282861 * k[2][m] + 0.924834003261792 * k[3][m]);
    }
    {
        let (kk, qq) = (&mut k[4], &mut kq[4]);
        f(4, &s, kk, qq);
    }
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] =
            y[m] + h * (0.037037037037037035 * k[0][m] + 0.17082860872947386 * k[3][m] + 0.12546768756682242 * k[4][m]);
    }
    {
        let (kk, qq) = (&mut k[5], &mut kq[5]);
        f(5, &s, kk, qq);
    }
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = y[m]
            + h * (0.037109375 * k[0][m]
                + 0.17025221101954405 * k[3][m]
                + 0.06021653898045596 * k[4][m]
                + -0.017578125 * k[5][m]);
    }
    {
        let (kk, qq) = (&mut k[6], &mut kq[6]);
        f(6, &s, kk, qq);
    }
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = y[m]
            + h * (0.03709200011850479 * k[0][m]
                + 0.17038392571223998 * k[3][m]
                + 0.10726203044637328 * k[4][m]
                + -0.015319437748624402 * k[5][m]
                + 0.008273789163814023 * k[6][m]);
    }
    {
        let (kk, qq) = (&mut k[7], &mut kq[7]);
        f(7, &s, kk, qq);
    }
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = y[m]
            + h * (0.6241109587160757 * k[0][m]
                + -3.3608926294469414 * k[3][m]
                + -0.868219346841726 * k[4][m]
                + 27.59209969944671 * k[5][m]
                + 20.154067550477894 * k[6][m]
                + -43.48988418106996 * k[7][m]);
    }
    {
        let (kk, qq) = (&mut k[8], &mut kq[8]);
        f(8, &s, kk, qq);
    }
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = y[m]
            + h * (0.47766253643826434 * k[0][m]
                + -2.4881146199716677 * k[3][m]
                + -0.590290826836843 * k[4][m]
                + 21.230051448181193 * k[5][m]
                + 15.279233632882423 * k[6][m]
                + -33.28821096898486 * k[7][m]
                + -0.020331201708508627 * k[8][m]);
    }
    {
        let (kk, qq) = (&mut k[9], &mut kq[9]);
        f(9, &s, kk, qq);
    }
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = y[m]
            + h * (-0.9371424300859873 * k[0][m]
                + 5.186372428844064 * k[3][m]
                + 1.0914373489967295 * k[4][m]
                + -8.149787010746927 * k[5][m]
                + -18.52006565999696 * k[6][m]
                + 22.739487099350505 * k[7][m]
                + 2.4936055526796523 * k[8][m]
                + -3.0467644718982196 * k[9][m]);
    }
    {
        let (kk, qq) = (&mut k[10], &mut kq[10]);
        f(10, &s, kk, qq);
    }
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = y[m]
            + h * (2.273310147516538 * k[0][m]
                + -10.53449546673725 * k[3][m]
                + -2.0008720582248625 * k[4][m]
                + -17.9589318631188 * k[5][m]
                + 27.94888452941996 * k[6][m]
                + -2.8589982771350235 * k[7][m]
                + -8.87285693353063 * k[8][m]
                + 12.360567175794303 * k[9][m]
                + 0.6433927460157636 * k[10][m]);
    }
    {
        let (kk, qq) = (&mut k[11], &mut kq[11]);
        f(11, &s, kk, qq);
    }
}

/// `Σ b_i·k_i`: the eighth-order solution's increment per unit step.
#[inline(always)]
#[allow(clippy::needless_range_loop)]
pub(super) fn weights_b<const N: usize>(k: &[[f64; N]; 13]) -> [f64; N] {
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = 0.054293734116568765 * k[0][m]
            + 4.450312892752409 * k[5][m]
            + 1.8915178993145003 * k[6][m]
            + -5.801203960010585 * k[7][m]
            + 0.3111643669578199 * k[8][m]
            + -0.1521609496625161 * k[9][m]
            + 0.20136540080403034 * k[10][m]
            + 0.04471061572777259 * k[11][m];
    }
    s
}

/// `Σ e5_i·k_i`: the fifth-order error estimate per unit step.
#[inline(always)]
#[allow(clippy::needless_range_loop)]
pub(super) fn weights_e5<const N: usize>(k: &[[f64; N]; 13]) -> [f64; N] {
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = 0.01312004499419488 * k[0][m]
            + -1.2251564463762044 * k[5][m]
            + -0.4957589496572502 * k[6][m]
            + 1.6643771824549864 * k[7][m]
            + -0.35032884874997366 * k[8][m]
            + 0.3341791187130175 * k[9][m]
            + 0.08192320648511571 * k[10][m]
            + -0.022355307863886294 * k[11][m];
    }
    s
}

/// `Σ e3_i·k_i`: the third-order error estimate per unit step.
#[inline(always)]
#[allow(clippy::needless_range_loop)]
pub(super) fn weights_e3<const N: usize>(k: &[[f64; N]; 13]) -> [f64; N] {
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = -0.18980075407240762 * k[0][m]
            + 4.450312892752409 * k[5][m]
            + 1.8915178993145003 * k[6][m]
            + -5.801203960010585 * k[7][m]
            + -0.4226823213237919 * k[8][m]
            + -0.1521609496625161 * k[9][m]
            + 0.20136540080403034 * k[10][m]
            + 0.02265179219836082 * k[11][m];
    }
    s
}

/// The dense-output stages 14 … 16 (`k[12]` holds the rate at the step's end).
#[inline(always)]
#[allow(clippy::needless_range_loop)]
pub(super) fn dense_stages<const N: usize>(
    y: &[f64; N],
    h: f64,
    k: &[[f64; N]; 13],
    kx: &mut [[f64; N]; 3],
    kqx: &mut [[f64; 3]; 3],
    mut f: impl FnMut(usize, &[f64; N], &mut [f64; N], &mut [f64; 3]),
) {
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = y[m]
            + h * (0.056167502283047954 * k[0][m]
                + 0.25350021021662483 * k[6][m]
                + -0.2462390374708025 * k[7][m]
                + -0.12419142326381637 * k[8][m]
                + 0.15329179827876568 * k[9][m]
                + 0.00820105229563469 * k[10][m]
                + 0.007567897660545699 * k[11][m]
                + -0.008298 * k[12][m]);
    }
    {
        let (kk, qq) = (&mut kx[0], &mut kqx[0]);
        f(13, &s, kk, qq);
    }
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = y[m]
            + h * (0.03183464816350214 * k[0][m]
                + 0.028300909672366776 * k[5][m]
                + 0.053541988307438566 * k[6][m]
                + -0.05492374857139099 * k[7][m]
                + -0.00010834732869724932 * k[10][m]
                + 0.0003825710908356584 * k[11][m]
                + -0.00034046500868740456 * k[12][m]
                + 0.1413124436746325 * kx[0][m]);
    }
    {
        let (kk, qq) = (&mut kx[1], &mut kqx[1]);
        f(14, &s, kk, qq);
    }
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = y[m]
            + h * (-0.42889630158379194 * k[0][m]
                + -4.697621415361164 * k[5][m]
                + 7.683421196062599 * k[6][m]
                + 4.06898981839711 * k[7][m]
                + 0.3567271874552811 * k[8][m]
                + -0.0013990241651590145 * k[12][m]
                + 2.9475147891527724 * kx[0][m]
                + -9.15095847217987 * kx[1][m]);
    }
    {
        let (kk, qq) = (&mut kx[2], &mut kqx[2]);
        f(15, &s, kk, qq);
    }
}

/// Row 1 of the dense-output matrix D: the interpolant's term F3 per unit step.
#[inline(always)]
#[allow(clippy::needless_range_loop)]
pub(super) fn weights_d0<const N: usize>(k: &[[f64; N]; 13], kx: &[[f64; N]; 3]) -> [f64; N] {
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = -8.428938276109013 * k[0][m]
            + 0.5667149535193777 * k[5][m]
            + -3.0689499459498917 * k[6][m]
            + 2.38466765651207 * k[7][m]
            + 2.117034582445028 * k[8][m]
            + -0.871391583777973 * k[9][m]
            + 2.2404374302607883 * k[10][m]
            + 0.6315787787694688 * k[11][m]
            + -0.08899033645133331 * k[12][m]
            + 18.148505520854727 * kx[0][m]
            + -9.194632392478356 * kx[1][m]
            + -4.436036387594894 * kx[2][m];
    }
    s
}

/// Row 2 of the dense-output matrix D: the interpolant's term F4 per unit step.
#[inline(always)]
#[allow(clippy::needless_range_loop)]
pub(super) fn weights_d1<const N: usize>(k: &[[f64; N]; 13], kx: &[[f64; N]; 3]) -> [f64; N] {
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = 10.427508642579134 * k[0][m]
            + 242.28349177525817 * k[5][m]
            + 165.20045171727028 * k[6][m]
            + -374.5467547226902 * k[7][m]
            + -22.113666853125306 * k[8][m]
            + 7.733432668472264 * k[9][m]
            + -30.674084731089398 * k[10][m]
            + -9.332130526430229 * k[11][m]
            + 15.697238121770845 * k[12][m]
            + -31.139403219565178 * kx[0][m]
            + -9.35292435884448 * kx[1][m]
            + 35.81684148639408 * kx[2][m];
    }
    s
}

/// Row 3 of the dense-output matrix D: the interpolant's term F5 per unit step.
#[inline(always)]
#[allow(clippy::needless_range_loop)]
pub(super) fn weights_d2<const N: usize>(k: &[[f64; N]; 13], kx: &[[f64; N]; 3]) -> [f64; N] {
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = 19.985053242002433 * k[0][m]
            + -387.0373087493518 * k[5][m]
            + -189.17813819516758 * k[6][m]
            + 527.8081592054236 * k[7][m]
            + -11.57390253995963 * k[8][m]
            + 6.8812326946963 * k[9][m]
            + -1.0006050966910838 * k[10][m]
            + 0.7777137798053443 * k[11][m]
            + -2.778205752353508 * k[12][m]
            + -60.19669523126412 * kx[0][m]
            + 84.32040550667716 * kx[1][m]
            + 11.99229113618279 * kx[2][m];
    }
    s
}

/// Row 4 of the dense-output matrix D: the interpolant's term F6 per unit step.
#[inline(always)]
#[allow(clippy::needless_range_loop)]
pub(super) fn weights_d3<const N: usize>(k: &[[f64; N]; 13], kx: &[[f64; N]; 3]) -> [f64; N] {
    let mut s = [0.0; N];
    for m in 0..N {
        s[m] = -25.69393346270375 * k[0][m]
            + -154.18974869023643 * k[5][m]
            + -231.5293791760455 * k[6][m]
            + 357.6391179106141 * k[7][m]
            + 93.40532418362432 * k[8][m]
            + -37.45832313645163 * k[9][m]
            + 104.0996495089623 * k[10][m]
            + 29.8402934266605 * k[11][m]
            + -43.53345659001114 * k[12][m]
            + 96.32455395918828 * kx[0][m]
            + -39.17726167561544 * kx[1][m]
            + -149.72683625798564 * kx[2][m];
    }
    s
}
