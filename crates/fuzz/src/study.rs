//! The study file target: the reader of study files (format "pliant-study",
//! `pliant.studies.spec.load_study`, docs/study.md) is Python, so this target hands each
//! input to one long-lived Python worker — an interpreter that has the `pliant` package
//! (`PLIANT_PYTHON`, the repository's `.venv`, or `python3`; `./scripts/install-python.sh`
//! installs it), running the study reader of this source tree — which writes it to a
//! study file of its own and reads it. The
//! reader never raises anything but `StudyError` (anything else is a find, as a panic is
//! for the Rust readers); a study it accepts has at least one run and one parameter, a
//! seed ≥ 0, only finite distribution numbers (bounds may be infinite for a normal
//! distribution, never NaN or reversed), finite grid levels and a finite positive
//! envelope voxel. The worker is started once and restarted after it dies (a death is a
//! find).

use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};
use std::sync::{Mutex, PoisonError};

/// The worker's program: length-prefixed inputs on stdin, one JSON reply line each.
const HARNESS: &str = r#"
import collections, json, math, os, pickle, struct, sys, tempfile, traceback, types
import pliant  # the engine (Scene.from_json for [scene_values])

# the study reader of this source tree (argv[1]), whatever copy is installed
studies = types.ModuleType("pliant.studies")
studies.__path__ = [sys.argv[1]]
sys.modules["pliant.studies"] = studies
from pliant.studies import spec
from pliant.studies.spec import StudyError, load_study

# The inputs are study files; the scenes they name do not change while fuzzing. So each
# scene file is parsed once (keyed by path, size and modification time; a copy handed
# out each time), and the engine's check of a scene with [scene_values] runs once per
# distinct scene text. Both caches keep the last 256 entries, so the worker's memory stays
# bounded however many inputs it reads; the fuzzed study file itself is never cached.
CACHED = 256


def remember(cache, key, make):
    """The value for `key` in `cache` (an OrderedDict of at most CACHED entries, the least
    recently used dropped first), made by `make()` when absent."""
    if key not in cache:
        cache[key] = make()
        if len(cache) > CACHED:
            cache.popitem(last=False)
    cache.move_to_end(key)
    return cache[key]


read_file = spec._read_toml
files = collections.OrderedDict()


def read_once(path, what):
    if what != "scene":
        return read_file(path, what)
    try:
        st = os.stat(path)
    except OSError:
        return read_file(path, what)  # its own message
    key = (os.path.abspath(path), what, st.st_size, st.st_mtime_ns)
    raw, text = remember(files, key, lambda: read_file(path, what))
    return pickle.loads(pickle.dumps(raw)), text  # plain data: a quick deep copy


spec._read_toml = read_once
build = pliant.Scene.from_json
checked = collections.OrderedDict()


def build_once(text, *args, **kwargs):
    def check():
        try:
            return build(text, *args, **kwargs), None
        except Exception as e:
            return None, e

    scene, error = remember(checked, (text, args, tuple(sorted(kwargs.items()))), check)
    if error is not None:
        raise error
    return scene


pliant.Scene.from_json = staticmethod(build_once)

folder = tempfile.mkdtemp(prefix="pliant-fuzz-study-")
path = os.path.join(folder, "study.toml")


def finite(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def broken(s):
    if not (isinstance(s.runs, int) and s.runs >= 1):
        return f"runs = {s.runs!r}"
    if not (isinstance(s.seed, int) and s.seed >= 0):
        return f"seed = {s.seed!r}"
    if not (isinstance(s.grid_levels, int) and s.grid_levels >= 1):
        return f"grid levels = {s.grid_levels!r}"
    if not s.parameters:
        return "no parameters"
    if s.envelope_voxel_m is not None and not (finite(s.envelope_voxel_m) and s.envelope_voxel_m > 0):
        return f"envelope voxel = {s.envelope_voxel_m!r}"
    for p in s.parameters:
        d = p.distribution
        if d.kind == "choice":
            if not d.choices:
                return f"parameter {p.name}: no choices"
            continue
        for k in ("mean", "std", "mode"):
            if not finite(getattr(d, k)):
                return f"parameter {p.name}: {k} = {getattr(d, k)!r}"
        if math.isnan(d.low) or math.isnan(d.high) or not d.low < d.high:
            return f"parameter {p.name}: bounds [{d.low!r}, {d.high!r}]"
        if d.kind in ("uniform", "triangular") and not (finite(d.low) and finite(d.high)):
            return f"parameter {p.name}: {d.kind} bounds [{d.low!r}, {d.high!r}]"
        if d.kind == "normal" and not d.std > 0:
            return f"parameter {p.name}: std = {d.std!r}"
        for v in p.levels or []:
            if not finite(v):
                return f"parameter {p.name}: level {v!r}"
    return None


stdin, stdout = sys.stdin.buffer, sys.stdout
stdout.write("ready\n")
stdout.flush()
while True:
    head = stdin.read(8)
    if len(head) < 8:
        break
    data = stdin.read(struct.unpack("<Q", head)[0])
    with open(path, "wb") as f:
        f.write(data)
    try:
        why = broken(load_study(path))
        reply = {"find": why} if why else {"ok": True}
    except StudyError as e:
        reply = {"ok": True} if str(e).strip() else {"find": "a StudyError without a message"}
    except Exception as e:
        reply = {"find": f"raised {type(e).__name__}: {e}\n{traceback.format_exc()}"[:4000]}
    stdout.write(json.dumps(reply) + "\n")
    stdout.flush()
"#;

/// A running worker.
struct Worker {
    child: Child,
    input: ChildStdin,
    output: BufReader<ChildStdout>,
}

impl Worker {
    fn start() -> Result<Worker, String> {
        let tried = pliant_runs::cad_converter::python_candidates();
        for python in &tried {
            let has = Command::new(python)
                .args(["-c", "import pliant"])
                .stdin(Stdio::null())
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .status()
                .is_ok_and(|s| s.success());
            if !has {
                continue;
            }
            let mut child = Command::new(python)
                .args(["-c", HARNESS])
                .arg(studies_source())
                .stdin(Stdio::piped())
                .stdout(Stdio::piped())
                .stderr(Stdio::null())
                .spawn()
                .map_err(|e| format!("starting {}: {e}", python.display()))?;
            let input = child.stdin.take().ok_or("no stdin")?;
            let mut output = BufReader::new(child.stdout.take().ok_or("no stdout")?);
            let mut line = String::new();
            output
                .read_line(&mut line)
                .map_err(|e| format!("the study worker: {e}"))?;
            if line.trim() != "ready" {
                return Err(format!("the study worker did not start: {line:?}"));
            }
            return Ok(Worker {
                child,
                input,
                output,
            });
        }
        let names: Vec<String> = tried.iter().map(|p| p.display().to_string()).collect();
        Err(format!(
            "the study target needs a Python with the package `pliant` (./scripts/install-python.sh \
             installs it into .venv, or name one with PLIANT_PYTHON); none of these has it: {}",
            names.join(", ")
        ))
    }

    /// The worker's reply to one input: `Ok` or the broken property.
    fn read(&mut self, input: &[u8]) -> std::io::Result<Result<(), String>> {
        self.input.write_all(&(input.len() as u64).to_le_bytes())?;
        self.input.write_all(input)?;
        self.input.flush()?;
        let mut line = String::new();
        if self.output.read_line(&mut line)? == 0 {
            return Err(std::io::Error::other("the worker closed its output"));
        }
        let reply: serde_json::Value = serde_json::from_str(&line)
            .map_err(|e| std::io::Error::other(format!("a reply that is not JSON: {e}")))?;
        Ok(match reply.get("find") {
            Some(what) => Err(what.as_str().unwrap_or("?").to_string()),
            None => Ok(()),
        })
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

static WORKER: Mutex<Option<Worker>> = Mutex::new(None);

/// The study reader's source in this tree (`pliant/studies`).
fn studies_source() -> std::path::PathBuf {
    std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../python/python/pliant/studies"
    ))
    .to_path_buf()
}

/// The study reader on one input (see the module doc).
pub fn study(input: &[u8]) -> Result<(), String> {
    let mut slot = WORKER.lock().unwrap_or_else(PoisonError::into_inner);
    if slot.is_none() {
        *slot = Some(Worker::start()?);
    }
    let worker = slot.as_mut().expect("started above");
    match worker.read(input) {
        Ok(outcome) => outcome,
        Err(e) => {
            let status = worker.child.try_wait().ok().flatten();
            *slot = None;
            Err(format!("the study reader's process died ({e}; {status:?})"))
        }
    }
}

/// The seeds: the engine-bay study (its scene named by absolute path, as the worker's
/// study file lies in a folder of its own) and a small study of the demo scene with every
/// kind of parameter and sampling field.
pub fn seeds() -> Vec<Vec<u8>> {
    let examples = crate::seeds::examples_dir();
    let examples = examples.canonicalize().unwrap_or(examples);
    let scene =
        |name: &str| toml::Value::String(examples.join(name).display().to_string()).to_string();
    let engine_bay = include_str!("../../../examples/engine_bay_study.toml").replace(
        "scene = \"engine_bay.toml\"",
        &format!("scene = {}", scene("engine_bay.toml")),
    );
    let demo = format!(
        r#"format = "pliant-study"
version = 1
name = "demo variants"
scene = {}
length_unit = "mm"
solver = "static"
ergonomics = "posture=sitting, population=men"

[sampling]
method = "grid"
runs = 12
seed = 3
levels = 2

[envelope]
voxel = 4
hoses = ["coolant"]

[[parameters]]
name = "e_t"
vary = "material"
material = "hose3"
property = "e_tension_mpa"
apply = "set"
distribution = "normal"
mean = 9.0
std = 1.5
min = 6
levels = [7.5, 9.0, 10.5]

[[parameters]]
vary = "hose_length"
hose = "coolant"
distribution = "uniform"
min = 0.98
max = 1.02

[[parameters]]
name = "who"
vary = "ergonomics"
choices = ["posture=standing", "posture=sitting, population=men"]

[[parameters]]
vary = "solver"
choices = ["explicit", "static"]

[[parameters]]
name = "d_outer"
vary = "scene_value"
path = "hoses[0].section.d_outer"
distribution = "triangular"
min = 34
mode = 35
max = 36
"#,
        scene("demo.toml")
    );
    vec![engine_bay.into_bytes(), demo.into_bytes()]
}
