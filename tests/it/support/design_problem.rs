//! The paper's design problem as `thud design` takes it: Table 3's design, its ball's mass and
//! clearance varied, the peak level minimised against the damping inclination maximised.

/// `thud design`'s arguments for the paper's problem; a test appends its budget, seed, outputs.
pub const PAPER_PROBLEM: [&str; 11] = [
    "design",
    "--preset",
    "paper-table3",
    "--vary",
    "mass=20g:120g",
    "--vary",
    "gap=1cm:6cm",
    "--minimize",
    "spl_max_db",
    "--maximize",
    "inclination_cm_s",
];

/// The paper's problem followed by `rest`.
pub fn paper_problem_with<'a>(rest: &[&'a str]) -> Vec<&'a str> {
    let mut args = PAPER_PROBLEM.to_vec();
    args.extend_from_slice(rest);
    args
}
