//! The results handed to Python: `Pulse`, `Run`, `Ensemble`, `Chart` and `Response`. Each is
//! made from the engine's result record ([`thud_core::report`]) — the very record the command
//! line prints with `--json` — so the two cannot drift: scalars are copied, lists of records
//! become dicts of NumPy arrays by [`columns`] (one array per key of the record), nested
//! objects become dicts. Every number is checked finite before it is handed out; a value that
//! does not exist (no impact, so no SPL) is `None`, or NaN inside a float array (zone 0 in a
//! zone array).
//!
//! Every result pickles (and `copy.deepcopy`s): `__reduce__` hands out the record's JSON
//! (floats written and read back exactly), and `thud._restore` builds the object again from it
//! by the same constructor, so an unpickled result is the same object field for field. Tables
//! and labelled arrays (`impacts_frame`, `to_dataframe`, `to_xarray`), `as_dict(json=True)` and
//! `_repr_html_` are Python code (`thud/_frames.py`) that these methods call.

mod chart;
mod convert;
mod ensemble;
mod pickle;
mod pulse;
mod response;
mod run;

pub use chart::PyChart;
pub use ensemble::PyEnsemble;
pub use pickle::_restore;
pub use pulse::{PulseData, PyPulse};
pub use response::PyResponse;
pub use run::{PyRun, RunData};
