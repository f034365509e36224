//! Resource limits on the command line (`--max-memory`, `--max-mesh-bytes`,
//! `--max-steps`): a scene beyond them is refused while it loads (or, for the steps,
//! before its run starts), naming the field and the estimate (`pliant_scene::budget`).

use pliant_scene::budget::{parse_bytes, DEFAULT_MAX_MEMORY_BYTES, DEFAULT_MAX_STEPS};
use pliant_scene::files::DEFAULT_MAX_FILE_BYTES;
use pliant_scene::{Limits, LoadOptions};

/// The limits every command that loads a scene takes.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct LimitArgs {
    /// Refuse scenes whose run would need more memory than this (estimated from their
    /// elements, triangles and hose–hose contact pairs), e.g. 8G, 512M [default: 4G].
    #[arg(long = "max-memory", value_parser = parse_bytes)]
    pub max_memory: Option<u64>,
    /// Largest mesh file read, e.g. 1G [default: 256M].
    #[arg(long = "max-mesh-bytes", value_parser = parse_bytes)]
    pub max_mesh_bytes: Option<u64>,
    #[command(flatten)]
    pub steps: StepLimit,
}

/// `--max-steps`: the step budget of every command that runs a simulation (`run`,
/// `serve`, `replay`, `export`, `study`), checked before the run starts.
#[derive(clap::Args, Clone, Copy, Debug, Default)]
pub struct StepLimit {
    /// Refuse runs planned at more steps than this (a timeline's duration over the time
    /// step; a replayed log's last tick) [default: 1000000000].
    #[arg(long = "max-steps")]
    pub max_steps: Option<u64>,
}

impl StepLimit {
    /// The limit given, or the default.
    pub fn get(&self) -> u64 {
        self.max_steps.unwrap_or(DEFAULT_MAX_STEPS)
    }
}

impl LimitArgs {
    /// How scenes from the user's own disk are loaded under these limits.
    pub fn load_options(&self) -> LoadOptions {
        LoadOptions {
            limits: Limits {
                max_steps: self.steps.get(),
                ..Limits::with_memory(self.max_memory.unwrap_or(DEFAULT_MAX_MEMORY_BYTES))
            },
            max_file_bytes: self.max_mesh_bytes.unwrap_or(DEFAULT_MAX_FILE_BYTES),
            sandboxed: false,
            ..pliant_runs::load_options()
        }
    }
}
