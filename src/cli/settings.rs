//! The user's settings as the CLI uses them: loaded once per run from the config directory, a
//! problem with the file printed as a one-line warning on stderr (the run goes on with the
//! defaults and the file is left as it is).

use std::sync::OnceLock;

use crate::config::{self, Config};

static CONFIG: OnceLock<Config> = OnceLock::new();

/// Loads the user's config (once), printing a warning if the file is unusable.
pub fn load() -> &'static Config {
    CONFIG.get_or_init(|| {
        let loaded = config::load_user_config();
        if let Some(w) = loaded.warning() {
            super::warn(&w);
        }
        loaded.config
    })
}
