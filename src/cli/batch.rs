//! `dicesim batch`: many rolls in parallel, per-roll results and their statistics.

use super::{CliError, EngineArg, INTERRUPTED, SetupArgs, cancel_on_ctrl_c, persist, temp_file_beside};
use crate::experiment::batch::thread_count;
use crate::experiment::ics::{parse_initial_conditions, record_csv_row, records_csv_header};
use crate::experiment::{BatchRun, BatchSummary, RollRecord, Rolls, RunOptions, stream_batch};
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde_json::json;
use std::io::{BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct BatchArgs {
    #[command(flatten)]
    pub setup: SetupArgs,
    /// Roll N dice with initial conditions drawn from the preset's `[random]` ranges.
    #[arg(
        long,
        value_name = "N",
        required_unless_present = "ics",
        conflicts_with = "ics"
    )]
    pub rolls: Option<u64>,
    /// Roll the initial conditions of a CSV file: a header with `id` and any of height,
    /// velocity_x|y|z, angular_velocity_x|y|z, angular_momentum_x|y|z, yaw, pitch, roll
    /// (missing columns take the preset's initial values).
    #[arg(long, value_name = "FILE.csv")]
    pub ics: Option<PathBuf>,
    /// Seed of the random draws (default: the preset's `random.seed`); roll i's draw depends
    /// on (seed, i) alone.
    #[arg(long, value_name = "S", conflicts_with = "ics")]
    pub seed: Option<u64>,
    /// Worker threads (default: one per core); the results do not depend on it.
    #[arg(long, value_name = "J", value_parser = clap::value_parser!(u64).range(1..))]
    pub jobs: Option<u64>,
    /// Write every roll (id, initial condition, start face, face, status, steps, simulated
    /// seconds) to a .csv or .json file.
    #[arg(long, value_name = "FILE.csv|FILE.json")]
    pub out: Option<PathBuf>,
    /// Print the summary as one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// The engine that steps the rolls; results are bit for bit the same with each.
    #[arg(long, value_enum, default_value_t = EngineArg::Auto)]
    pub engine: EngineArg,
}

/// The per-roll file's format, from its extension.
enum OutFormat {
    Csv,
    Json,
}

fn out_format(path: &Path) -> Result<OutFormat, CliError> {
    match path.extension().and_then(|e| e.to_str()) {
        Some("csv") => Ok(OutFormat::Csv),
        Some("json") => Ok(OutFormat::Json),
        _ => Err(CliError::Input(format!(
            "--out {}: expected a .csv or .json file",
            path.display()
        ))),
    }
}

pub fn run(args: &BatchArgs) -> Result<(), CliError> {
    let preset = args.setup.resolve()?;
    let params = preset.params();
    params.validate().map_err(|e| CliError::Input(e.to_string()))?;
    let format = args.out.as_deref().map(out_format).transpose()?;
    let seed = args.seed.unwrap_or(preset.random.seed);
    let given = match &args.ics {
        Some(path) => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| CliError::Input(format!("--ics {}: {e}", path.display())))?;
            let ics = parse_initial_conditions(&text, &preset.initial, params.inertia())
                .map_err(|e| CliError::Input(format!("--ics {}: {e}", path.display())))?;
            Some(ics)
        }
        None => None,
    };
    let rolls = match &given {
        Some(ics) => Rolls::Given(ics),
        None => Rolls::Random {
            ranges: &preset.random,
            base: &preset.initial,
            seed,
            count: args.rolls.unwrap_or(0),
        },
    };
    let jobs = thread_count(args.jobs.unwrap_or(0) as usize);
    let options = RunOptions {
        jobs,
        engine: args.engine.engine(),
    };
    let stop = cancel_on_ctrl_c()?;

    let bar = if std::io::stderr().is_terminal() {
        ProgressBar::new(rolls.len())
    } else {
        ProgressBar::with_draw_target(Some(rolls.len()), ProgressDrawTarget::hidden())
    };
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} rolls, {per_sec}, {eta} left")
            .expect("the progress template is valid"),
    );
    let seed_field = if given.is_some() { None } else { Some(seed) };
    // Records go to the file as they arrive, so memory stays flat in the number of rolls;
    // the file appears under its name only once it is whole (or an interrupted prefix).
    let mut writer = match (&args.out, &format) {
        (Some(path), Some(format)) => Some(
            RecordWriter::create(path, format, seed_field, rolls.len())
                .map_err(|e| CliError::Run(format!("{}: {e}", path.display())))?,
        ),
        _ => None,
    };
    let run = stream_batch(&params, &rolls, &options, &stop, &mut |chunk: &[RollRecord]| {
        bar.inc(chunk.len() as u64);
        match &mut writer {
            Some(w) => w.write(chunk).map_err(|e| e.to_string()),
            None => Ok(()),
        }
    })
    .map_err(|e| match e {
        crate::experiment::Error::Output(msg) => CliError::Run(format!(
            "{}: {msg}",
            args.out.as_deref().unwrap_or(Path::new("")).display()
        )),
        e => CliError::Input(e.to_string()),
    })?;
    bar.finish_and_clear();

    let summary = &run.summary;
    if let (Some(w), Some(path)) = (writer, &args.out) {
        w.finish(&run)
            .map_err(|e| CliError::Run(format!("{}: {e}", path.display())))?;
    }
    let mut out = std::io::stdout().lock();
    if args.json {
        let v = json!({
            "preset": preset.name,
            "seed": seed_field,
            "requested": run.requested,
            "completed": run.completed,
            "interrupted": run.cancelled,
            "jobs": run.jobs,
            "engine": run.engine,
            "summary": summary,
        });
        writeln!(out, "{v}")?;
    } else {
        print_summary(&mut out, &run, summary)?;
    }
    out.flush()?;
    if run.cancelled {
        eprintln!(
            "dicesim: interrupted: kept the {} of {} rolls completed{}",
            run.completed,
            run.requested,
            match &args.out {
                Some(path) => format!(" (the first {} in {})", run.completed, path.display()),
                None => String::new(),
            }
        );
        std::process::exit(INTERRUPTED);
    }
    Ok(())
}

/// A per-roll file written as the records arrive: into a temporary file beside the target,
/// renamed onto it once complete, so a failed run leaves no partial file under the name.
struct RecordWriter {
    file: BufWriter<tempfile::NamedTempFile>,
    path: PathBuf,
    format: OutFormat,
    first: bool,
}

impl RecordWriter {
    fn create(path: &Path, format: &OutFormat, seed: Option<u64>, requested: u64) -> std::io::Result<Self> {
        let mut file = temp_file_beside(path)?;
        let format = match format {
            OutFormat::Csv => {
                writeln!(file, "{}", records_csv_header())?;
                OutFormat::Csv
            }
            OutFormat::Json => {
                // The rolls first, then what is known only at the end.
                write!(
                    file,
                    "{{\"seed\":{},\"requested\":{requested},\"rolls\":[",
                    json!(seed)
                )?;
                OutFormat::Json
            }
        };
        Ok(RecordWriter {
            file,
            path: path.to_path_buf(),
            format,
            first: true,
        })
    }

    fn write(&mut self, records: &[RollRecord]) -> std::io::Result<()> {
        for r in records {
            match self.format {
                OutFormat::Csv => writeln!(self.file, "{}", record_csv_row(r))?,
                OutFormat::Json => {
                    if !self.first {
                        self.file.write_all(b",")?;
                    }
                    serde_json::to_writer(&mut self.file, r)?;
                }
            }
            self.first = false;
        }
        Ok(())
    }

    fn finish(mut self, run: &BatchRun) -> std::io::Result<()> {
        if let OutFormat::Json = self.format {
            writeln!(
                self.file,
                "],\"interrupted\":{},\"summary\":{}}}",
                run.cancelled,
                json!(run.summary)
            )?;
        }
        persist(self.file, &self.path)
    }
}

fn print_summary(out: &mut impl Write, run: &BatchRun, s: &BatchSummary) -> std::io::Result<()> {
    writeln!(
        out,
        "{} rolls on {} thread{}, {} engine",
        s.rolls,
        run.jobs,
        if run.jobs == 1 { "" } else { "s" },
        run.engine.name()
    )?;
    writeln!(out, "face   count   share")?;
    for f in 0..6 {
        writeln!(
            out,
            "{:>4} {:>7}  {:>5.1}%",
            f + 1,
            s.faces.counts[f],
            100.0 * s.face_shares[f]
        )?;
    }
    match (s.chi_square, s.p_value) {
        (Some(chi2), Some(p)) => writeln!(out, "χ² against a fair die  {chi2:.3} (5 dof), p = {p:.4}")?,
        _ => writeln!(out, "χ² against a fair die  n/a (no faces)")?,
    }
    let [same, adjacent, opposite] = s.start_face_shares.map(|x| 100.0 * x);
    writeln!(
        out,
        "from the start face    same {same:.1}%, adjacent {adjacent:.1}%, opposite {opposite:.1}%"
    )?;
    let st = &s.status;
    writeln!(
        out,
        "status                 settled {}, settled without a face {}, did not settle {}, unstable {}",
        st.settled, st.settled_without_face, st.timeout, st.unstable
    )?;
    writeln!(
        out,
        "speed                  {:.0} rolls/s, {:.1} M steps/s ({} steps in {:.2} s)",
        s.rolls_per_s,
        s.steps_per_s / 1e6,
        s.steps,
        s.elapsed_s
    )?;
    Ok(())
}
