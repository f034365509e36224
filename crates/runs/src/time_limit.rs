//! Waiting for an external program with a time limit (a STEP file
//! with 1e308 or NaN coordinates made the converter run for ever): the child's output
//! is collected as it comes, and a child still running at the limit is killed.

use std::io::Read;
use std::process::{Child, Output};
use std::time::{Duration, Instant};

/// How often a running child is looked at.
const POLL: Duration = Duration::from_millis(20);

/// The child ran out of time and was killed; what it had written by then.
#[derive(Debug)]
pub struct TimedOut {
    pub limit: Duration,
    pub stderr: String,
}

/// Waits for `child` (stdout and stderr piped) to exit, at most `limit`; kills it at the
/// limit. Its stdout and stderr are read meanwhile, so a child writing much never
/// blocks on a full pipe.
pub fn output_within(
    mut child: Child,
    limit: Duration,
) -> std::io::Result<Result<Output, TimedOut>> {
    let drain = |pipe: Option<Box<dyn Read + Send>>| {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            if let Some(mut p) = pipe {
                let _ = p.read_to_end(&mut bytes);
            }
            bytes
        })
    };
    let stdout = drain(
        child
            .stdout
            .take()
            .map(|p| Box::new(p) as Box<dyn Read + Send>),
    );
    let stderr = drain(
        child
            .stderr
            .take()
            .map(|p| Box::new(p) as Box<dyn Read + Send>),
    );
    let deadline = Instant::now() + limit;
    let status = loop {
        if let Some(status) = child.try_wait()? {
            break Some(status);
        }
        if Instant::now() >= deadline {
            child.kill()?;
            child.wait()?;
            break None;
        }
        std::thread::sleep(POLL);
    };
    let stdout = stdout.join().unwrap_or_default();
    let stderr = stderr.join().unwrap_or_default();
    Ok(match status {
        Some(status) => Ok(Output {
            status,
            stdout,
            stderr,
        }),
        None => Err(TimedOut {
            limit,
            stderr: String::from_utf8_lossy(&stderr).into_owned(),
        }),
    })
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use std::process::{Command, Stdio};

    fn sh(script: &str) -> Child {
        Command::new("sh")
            .args(["-c", script])
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    }

    #[test]
    fn a_child_that_finishes_gives_its_output() {
        let out = output_within(sh("echo out; echo err >&2"), Duration::from_secs(60))
            .unwrap()
            .unwrap();
        assert!(out.status.success());
        assert_eq!(out.stdout, b"out\n");
        assert_eq!(out.stderr, b"err\n");
    }

    #[test]
    fn a_child_that_runs_on_is_killed_at_the_limit() {
        // `exec` so that the killed process is the sleeper itself (its pipes then close)
        let timed_out = output_within(
            sh("echo started >&2; exec sleep 1000"),
            Duration::from_millis(200),
        )
        .unwrap()
        .unwrap_err();
        assert_eq!(timed_out.limit, Duration::from_millis(200));
        assert_eq!(timed_out.stderr, "started\n");
    }
}
