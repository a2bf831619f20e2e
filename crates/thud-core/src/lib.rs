//! thud-core — the physics of single-unit impact dampers and the noise they make.
//!
//! Pure: no I/O, no terminal, no command line. Equation numbers refer to the source paper; the
//! model as the code implements it — conventions, the paper's errors, the reference values the
//! tests check — is stated in the repository's `docs/model.md`, cited as "docs/model.md §N".
//! SI units throughout; the front ends (the `thud` crate) convert at the edges.
//!
//! - [`contact`]: Hertz contact of one impact (Eqs 1–8) and materials.
//! - [`acoustics`]: the sound of one impact (Eqs 9–24): impulse response, closed form, image
//!   sources, levels and directivity.
//! - [`damper`]: the 2-DOF impact damper (Eqs 25–26): exact flight, the event-driven solver and
//!   the Newmark-β reference.
//! - [`design`]: a whole design, its metrics (Eq 27), zones and the design chart (sweep).
//! - [`dynamics`]: orbits of a forced design: bifurcation diagrams, orbit types, impact maps, basins.
//! - [`continuation`]: pseudo-arclength continuation of periodic orbits, with their bifurcations.
//! - [`orbit`]: periodic orbits of a forced design by shooting, with their Floquet multipliers.
//! - [`ensemble`]: N runs of a design from evenly spread initial ball offsets, and the
//!   spread of their metrics (p10 / median / p90, zone-3 probability).
//! - [`paper`]: the paper's tables and figures recomputed, with the paper's numbers beside them.
//! - [`fit`]: calibration from measurements: the structure's f_n, ζ, K, C and a damper's c1.
//! - [`finite`]: the check that every number of a result is finite before it is handed out.
//! - [`limits`]: the range of every parameter and the work cap of every run.
//! - [`params`]: named parameters (the command line's flags, Python's keywords) to a checked design.
//! - [`schema`]: the one data schema: every table's columns (name, unit, meaning) in order.
//! - [`response`]: a forced design's steady state and level (`Leq`), and its frequency response.
//! - [`study`]: studies over any numeric parameter (`--vary NAME=FROM:TO:N`).
//! - [`units`]: parsing and formatting of quantities with units.
//! - [`walk`]: one walk over a value's serialized form (every field and number), for the finite
//!   check and the explorer's cache keys.

pub mod acoustics;
pub mod contact;
pub mod continuation;
pub mod damper;
pub mod design;
mod draws;
pub mod dynamics;
pub mod ensemble;
pub mod error;
pub mod finite;
pub mod fit;
pub mod limits;
pub mod orbit;
pub mod paper;
pub mod params;
pub mod report;
pub mod response;
pub mod schema;
pub mod study;
pub mod units;
pub mod verdict;
pub mod walk;

pub use error::ThudError;
