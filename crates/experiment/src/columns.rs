//! The one table of a roll record's columns ([`COLUMNS`]): each column's name, unit and
//! type, how its cell is taken from a record and put back into one, and how a value read back
//! from a file is checked against the setup ([`RecordCheck`]). The CSV (`ics.rs`), the Parquet
//! schema, writer and reader (`parquet.rs`), merging (`merge/batch.rs`), `batch --versus`'s
//! file (`batch_sweep.rs`) and the checks of records read back all read it: a new column is
//! one row here (and the field of the record it shows).

use crate::data_file::{Column, Kind};
use crate::record::RollRecord;
use crate::stats::numbers_words;
use dicesim_physics::initial::limits;
use dicesim_physics::lanes;
use dicesim_physics::{
    FirstImpact, InitialCondition, Outcome, Params, Placement, Status, face_most_nearly_up,
};
use dicesim_setup::keys::column_name;
use dicesim_setup::number::StepClock;
use std::sync::LazyLock;

/// One cell of a record: what a column holds for one roll.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Cell<'a> {
    /// No value: the other spin form's, a face of a roll that did not settle, …
    Empty,
    Whole(u64),
    Real(f64),
    Word(&'a str),
}

impl Cell<'_> {
    pub(crate) fn whole(self) -> Option<u64> {
        match self {
            Cell::Whole(n) => Some(n),
            _ => None,
        }
    }

    pub(crate) fn small(self) -> Option<u8> {
        u8::try_from(self.whole()?).ok()
    }

    pub(crate) fn real(self) -> Option<f64> {
        match self {
            Cell::Real(x) => Some(x),
            _ => None,
        }
    }

    /// The same cell bit for bit (`-0.0` is not `0.0`, as in a file).
    pub(crate) fn same(self, other: Cell<'_>) -> bool {
        match (self, other) {
            (Cell::Empty, Cell::Empty) => true,
            (Cell::Whole(a), Cell::Whole(b)) => a == b,
            (Cell::Real(a), Cell::Real(b)) => a.to_bits() == b.to_bits(),
            (Cell::Word(a), Cell::Word(b)) => a == b,
            _ => false,
        }
    }
}

/// How a column's values are stored: in a CSV they are written as [`Kind`] says, in Parquet as
/// the physical and logical type named here.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Type {
    /// A whole number ≥ 0 (Parquet `INT64`, unsigned 64 bit).
    Count,
    /// A number a die shows, 0 to 255 (Parquet `INT32`, unsigned 8 bit): which numbers
    /// its die shows is the setup's ([`RecordCheck::is_face`]).
    Face,
    /// A double, written in its shortest round-trip form.
    Real,
    /// A word (Parquet `BYTE_ARRAY`, UTF-8).
    Word,
}

impl Type {
    /// The type a CSV's sidecar names.
    pub(crate) fn kind(self) -> Kind {
        match self {
            Type::Count | Type::Face => Kind::Integer,
            Type::Real => Kind::Real,
            Type::Word => Kind::Text,
        }
    }

    /// The Parquet schema's type, around the column's name.
    pub(crate) fn parquet(self, name: &str) -> String {
        match self {
            Type::Count => format!("INT64 {name} (INTEGER(64,false))"),
            Type::Face => format!("INT32 {name} (INTEGER(8,false))"),
            Type::Real => format!("DOUBLE {name}"),
            Type::Word => format!("BYTE_ARRAY {name} (STRING)"),
        }
    }
}

/// What a column says of a roll: the throw (the same in both setups of `batch --versus`) or
/// how it ended (one column per setup there).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Stage {
    Throw,
    Ending,
}

/// The two ways a start's spin is stated; a file has the columns of the forms its rolls were
/// given ([`SpinColumns`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum SpinForm {
    AngularVelocity,
    AngularMomentum,
}

/// One column of a roll record.
pub(crate) struct RecordColumn {
    /// The quantity's name; the column's is it with its unit ([`RecordColumn::name`]).
    quantity: &'static str,
    /// Its unit (`""` for counts, faces and words).
    unit: &'static str,
    pub(crate) ty: Type,
    pub(crate) stage: Stage,
    /// The spin form it states, for a spin column (present in a file by its [`SpinColumns`]).
    pub(crate) spin: Option<SpinForm>,
    /// Whether a roll may leave it empty (beside the other spin form's cells).
    optional: bool,
    /// The cell of a record.
    pub(crate) get: fn(&RollRecord) -> Cell<'static>,
    /// Puts a non-empty cell read back into a record; `None`: not a value of this column.
    set: fn(&mut RollRecord, Cell<'_>) -> Option<()>,
    /// Checks the value of a record read back against the setup, after the start's checks
    /// and those of the columns before it; the error without the roll's id.
    check: Option<Check>,
}

/// A column's check of a record read back ([`RecordColumn::check`]).
type Check = fn(&RecordCheck, &RollRecord) -> Result<(), String>;

impl RecordColumn {
    /// The column's name with its unit: `height_cm`, `time_s`, `face`.
    pub(crate) fn name(&self) -> &'static str {
        static NAMES: LazyLock<Vec<String>> =
            LazyLock::new(|| COLUMNS.iter().map(|c| column_name(c.quantity, c.unit)).collect());
        let at = COLUMNS
            .iter()
            .position(|c| std::ptr::eq(c, self))
            .expect("a column of the table");
        NAMES[at].as_str()
    }

    /// Whether it is a value of the start (a real of the throw): what a seeded sweep's draw
    /// gives, and what `--ics` reads.
    pub(crate) fn of_start(&self) -> bool {
        self.stage == Stage::Throw && self.ty == Type::Real
    }

    /// The quantity's name without its unit, as dicesim 0.1's `--ics` files named it.
    pub(crate) fn quantity(&self) -> &'static str {
        self.quantity
    }

    /// Whether a file with spin columns `spin` has this column.
    fn in_file(&self, spin: SpinColumns) -> bool {
        self.spin.is_none_or(|form| spin.states(form))
    }

    /// Whether a cell of it may be empty in a file with spin columns `spin`.
    pub(crate) fn nullable(&self, spin: SpinColumns) -> bool {
        self.optional || (self.spin.is_some() && spin == SpinColumns::Both)
    }
}

/// A start's column: `quantity` in `unit`, always given.
const fn start(
    quantity: &'static str,
    unit: &'static str,
    get: fn(&RollRecord) -> Cell<'static>,
    set: fn(&mut RollRecord, Cell<'_>) -> Option<()>,
) -> RecordColumn {
    RecordColumn {
        quantity,
        unit,
        ty: Type::Real,
        stage: Stage::Throw,
        spin: None,
        optional: false,
        get,
        set,
        check: None,
    }
}

/// A spin column of form `form`, empty in a row of the other form.
const fn spin(
    quantity: &'static str,
    form: SpinForm,
    get: fn(&RollRecord) -> Cell<'static>,
    set: fn(&mut RollRecord, Cell<'_>) -> Option<()>,
) -> RecordColumn {
    let unit = match form {
        SpinForm::AngularVelocity => limits::ANGULAR_VELOCITY.unit,
        SpinForm::AngularMomentum => limits::ANGULAR_MOMENTUM.unit,
    };
    RecordColumn {
        spin: Some(form),
        ..start(quantity, unit, get, set)
    }
}

/// Component `i` of the angular velocity of a start given it (empty for one given its
/// angular momentum: the angular velocity is then not the spin).
fn angular_velocity(r: &RollRecord, i: usize) -> Cell<'static> {
    match r.initial.angular_momentum {
        Some(_) => Cell::Empty,
        None => Cell::Real(r.initial.angular_velocity[i]),
    }
}

fn angular_momentum(r: &RollRecord, i: usize) -> Cell<'static> {
    r.initial
        .angular_momentum
        .map_or(Cell::Empty, |l| Cell::Real(l[i]))
}

/// Puts `value`, if it is one, into `field`.
fn put<T>(field: &mut T, value: Option<T>) -> Option<()> {
    *field = value?;
    Some(())
}

fn set_angular_momentum(r: &mut RollRecord, i: usize, c: Cell<'_>) -> Option<()> {
    r.initial.angular_momentum.get_or_insert([0.0; 3])[i] = c.real()?;
    Some(())
}

/// The first impact's `step`, `time_s` or `face_down` (empty for a roll without one).
fn first_impact(r: &RollRecord, cell: fn(&FirstImpact) -> Cell<'static>) -> Cell<'static> {
    r.outcome.first_impact.as_ref().map_or(Cell::Empty, cell)
}

/// The first impact of a record being read back, made when its first cell is read.
fn first_impact_mut(r: &mut RollRecord) -> &mut FirstImpact {
    r.outcome.first_impact.get_or_insert(FirstImpact {
        step: 0,
        time_s: 0.0,
        face_down: 0,
    })
}

/// Every column of a roll record, in the order of a file's columns.
pub(crate) static COLUMNS: [RecordColumn; 23] = [
    RecordColumn {
        quantity: "id",
        unit: "",
        ty: Type::Count,
        stage: Stage::Throw,
        spin: None,
        optional: false,
        get: |r| Cell::Whole(r.id),
        set: |r, c| put(&mut r.id, c.whole()),
        check: None,
    },
    start(
        "height",
        limits::HEIGHT.unit,
        |r| Cell::Real(r.initial.height),
        |r, c| put(&mut r.initial.height, c.real()),
    ),
    start(
        "velocity_x",
        limits::VELOCITY.unit,
        |r| Cell::Real(r.initial.velocity[0]),
        |r, c| put(&mut r.initial.velocity[0], c.real()),
    ),
    start(
        "velocity_y",
        limits::VELOCITY.unit,
        |r| Cell::Real(r.initial.velocity[1]),
        |r, c| put(&mut r.initial.velocity[1], c.real()),
    ),
    start(
        "velocity_z",
        limits::VELOCITY.unit,
        |r| Cell::Real(r.initial.velocity[2]),
        |r, c| put(&mut r.initial.velocity[2], c.real()),
    ),
    spin(
        "angular_velocity_x",
        SpinForm::AngularVelocity,
        |r| angular_velocity(r, 0),
        |r, c| put(&mut r.initial.angular_velocity[0], c.real()),
    ),
    spin(
        "angular_velocity_y",
        SpinForm::AngularVelocity,
        |r| angular_velocity(r, 1),
        |r, c| put(&mut r.initial.angular_velocity[1], c.real()),
    ),
    spin(
        "angular_velocity_z",
        SpinForm::AngularVelocity,
        |r| angular_velocity(r, 2),
        |r, c| put(&mut r.initial.angular_velocity[2], c.real()),
    ),
    spin(
        "angular_momentum_x",
        SpinForm::AngularMomentum,
        |r| angular_momentum(r, 0),
        |r, c| set_angular_momentum(r, 0, c),
    ),
    spin(
        "angular_momentum_y",
        SpinForm::AngularMomentum,
        |r| angular_momentum(r, 1),
        |r, c| set_angular_momentum(r, 1, c),
    ),
    spin(
        "angular_momentum_z",
        SpinForm::AngularMomentum,
        |r| angular_momentum(r, 2),
        |r, c| set_angular_momentum(r, 2, c),
    ),
    start(
        "yaw",
        limits::ORIENTATION.unit,
        |r| Cell::Real(r.initial.orientation[0]),
        |r, c| put(&mut r.initial.orientation[0], c.real()),
    ),
    start(
        "pitch",
        limits::ORIENTATION.unit,
        |r| Cell::Real(r.initial.orientation[1]),
        |r, c| put(&mut r.initial.orientation[1], c.real()),
    ),
    start(
        "roll",
        limits::ORIENTATION.unit,
        |r| Cell::Real(r.initial.orientation[2]),
        |r, c| put(&mut r.initial.orientation[2], c.real()),
    ),
    RecordColumn {
        quantity: "start_face",
        unit: "",
        ty: Type::Face,
        stage: Stage::Throw,
        spin: None,
        optional: false,
        get: |r| Cell::Whole(u64::from(r.start_face)),
        set: |r, c| put(&mut r.start_face, c.small()),
        check: Some(|check, r| {
            let face = check.start_face(&r.initial);
            match r.start_face == face {
                true => Ok(()),
                false => Err(format!(
                    "start_face {} is not the face its start puts up ({face})",
                    r.start_face
                )),
            }
        }),
    },
    RecordColumn {
        quantity: "face",
        unit: "",
        ty: Type::Face,
        stage: Stage::Ending,
        spin: None,
        optional: true,
        get: |r| r.outcome.face.map_or(Cell::Empty, |f| Cell::Whole(u64::from(f))),
        set: |r, c| put(&mut r.outcome.face, c.small().map(Some)),
        check: Some(|check, r| {
            let o = &r.outcome;
            match (o.status, o.face) {
                (_, Some(f)) if !check.is_face(f) => Err(check.not_a_face("face", f)),
                (Status::Timeout | Status::Unstable, Some(f)) => Err(format!(
                    "face {f} with status `{}` (only a settled roll has a face)",
                    o.status.name()
                )),
                _ => Ok(()),
            }
        }),
    },
    RecordColumn {
        quantity: "status",
        unit: "",
        ty: Type::Word,
        stage: Stage::Ending,
        spin: None,
        optional: false,
        get: |r| Cell::Word(r.outcome.status.name()),
        set: |r, c| match c {
            Cell::Word(w) => put(&mut r.outcome.status, Status::from_name(w)),
            _ => None,
        },
        check: None,
    },
    RecordColumn {
        quantity: "steps",
        unit: "",
        ty: Type::Count,
        stage: Stage::Ending,
        spin: None,
        optional: false,
        get: |r| Cell::Whole(r.outcome.steps),
        set: |r, c| put(&mut r.outcome.steps, c.whole()),
        check: Some(|check, r| {
            let (o, max_steps) = (&r.outcome, check.max_steps);
            match o.steps > max_steps || (o.status == Status::Timeout && o.steps != max_steps) {
                false => Ok(()),
                true => Err(format!(
                    "{} steps with status `{}`, but a roll times out at exactly {max_steps} steps",
                    o.steps,
                    o.status.name()
                )),
            }
        }),
    },
    RecordColumn {
        quantity: "time",
        unit: "s",
        ty: Type::Real,
        stage: Stage::Ending,
        spin: None,
        optional: false,
        get: |r| Cell::Real(r.outcome.time_s),
        set: |r, c| put(&mut r.outcome.time_s, c.real()),
        check: Some(|check, r| check.steps_time("time_s", r.outcome.steps, r.outcome.time_s)),
    },
    RecordColumn {
        quantity: "impacts",
        unit: "",
        ty: Type::Count,
        stage: Stage::Ending,
        spin: None,
        optional: false,
        get: |r| Cell::Whole(r.outcome.impacts),
        set: |r, c| put(&mut r.outcome.impacts, c.whole()),
        // Each impact begins after a state clear of the table; a first impact exactly when
        // there was one.
        check: Some(|_, r| {
            let o = &r.outcome;
            match (o.impacts, &o.first_impact) {
                (n, _) if n > o.steps.div_ceil(2) => Err(format!(
                    "{n} impacts in {} steps: each needs a step clear of the table",
                    o.steps
                )),
                (0, Some(_)) => Err("a first impact with 0 impacts".to_string()),
                (n, None) if n > 0 => Err(format!("{n} impacts but no first impact")),
                _ => Ok(()),
            }
        }),
    },
    RecordColumn {
        quantity: "first_impact_steps",
        unit: "",
        ty: Type::Count,
        stage: Stage::Ending,
        spin: None,
        optional: true,
        get: |r| first_impact(r, |f| Cell::Whole(f.step)),
        set: |r, c| put(&mut first_impact_mut(r).step, c.whole()),
        check: Some(|_, r| match &r.outcome.first_impact {
            Some(f) if f.step == 0 || f.step > r.outcome.steps => Err(format!(
                "first impact at step {}, outside the roll's steps 1 to {}",
                f.step, r.outcome.steps
            )),
            _ => Ok(()),
        }),
    },
    RecordColumn {
        quantity: "first_impact_time",
        unit: "s",
        ty: Type::Real,
        stage: Stage::Ending,
        spin: None,
        optional: true,
        get: |r| first_impact(r, |f| Cell::Real(f.time_s)),
        set: |r, c| put(&mut first_impact_mut(r).time_s, c.real()),
        check: Some(|check, r| match &r.outcome.first_impact {
            Some(f) => check.steps_time("first_impact_time_s", f.step, f.time_s),
            None => Ok(()),
        }),
    },
    RecordColumn {
        quantity: "first_impact_face_down",
        unit: "",
        ty: Type::Face,
        stage: Stage::Ending,
        spin: None,
        optional: true,
        get: |r| first_impact(r, |f| Cell::Whole(u64::from(f.face_down))),
        set: |r, c| put(&mut first_impact_mut(r).face_down, c.small()),
        check: Some(|check, r| match &r.outcome.first_impact {
            Some(f) if !check.is_face(f.face_down) => {
                Err(check.not_a_face("first_impact_face_down", f.face_down))
            }
            _ => Ok(()),
        }),
    },
];

/// Which forms of the spin a records file has columns for: those its rolls were given.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SpinColumns {
    /// Every roll was given an angular velocity (every random draw is).
    AngularVelocity,
    /// Every roll was given an angular momentum.
    AngularMomentum,
    /// Some of each: each row fills its own form's cells and leaves the other's empty.
    Both,
}

impl SpinColumns {
    /// The three layouts.
    pub(crate) const ALL: [SpinColumns; 3] = [
        SpinColumns::AngularVelocity,
        SpinColumns::AngularMomentum,
        SpinColumns::Both,
    ];

    /// The columns for rolls from `starts` (the angular velocity for none).
    pub fn of_starts<'a>(starts: impl IntoIterator<Item = &'a InitialCondition>) -> SpinColumns {
        let (mut velocity, mut momentum) = (false, false);
        for ic in starts {
            match ic.angular_momentum {
                Some(_) => momentum = true,
                None => velocity = true,
            }
        }
        match (velocity, momentum) {
            (_, false) => SpinColumns::AngularVelocity,
            (false, true) => SpinColumns::AngularMomentum,
            (true, true) => SpinColumns::Both,
        }
    }

    /// Whether the file has the columns of spin form `form`.
    fn states(self, form: SpinForm) -> bool {
        match self {
            SpinColumns::AngularVelocity => form == SpinForm::AngularVelocity,
            SpinColumns::AngularMomentum => form == SpinForm::AngularMomentum,
            SpinColumns::Both => true,
        }
    }

    /// Whether a roll with this start can be written in these columns.
    pub fn holds(self, ic: &InitialCondition) -> bool {
        match ic.angular_momentum {
            Some(_) => self != SpinColumns::AngularVelocity,
            None => self != SpinColumns::AngularMomentum,
        }
    }

    /// The columns of a file with these spin columns, in order (worked out once: a merge
    /// asks for them at every row).
    pub(crate) fn columns(self) -> &'static [&'static RecordColumn] {
        static LAYOUTS: LazyLock<[Vec<&'static RecordColumn>; 3]> = LazyLock::new(|| {
            SpinColumns::ALL.map(|spin| COLUMNS.iter().filter(|c| c.in_file(spin)).collect())
        });
        let at = SpinColumns::ALL
            .iter()
            .position(|s| *s == self)
            .expect("one of the layouts");
        &LAYOUTS[at]
    }
}

/// The columns of a per-roll file and their types, as its sidecar states them.
pub fn records_columns(spin: SpinColumns) -> Vec<Column> {
    (spin.columns().iter())
        .map(|c| Column {
            name: c.name().to_string(),
            kind: c.ty.kind(),
        })
        .collect()
}

/// A record with nothing read into it yet.
fn blank() -> RollRecord {
    RollRecord {
        id: 0,
        initial: InitialCondition::default(),
        start_face: 0,
        outcome: Outcome {
            status: Status::Settled,
            face: None,
            steps: 0,
            time_s: 0.0,
            impacts: 0,
            first_impact: None,
        },
    }
}

/// The record whose cells are `cells`, those of `columns`. Where `start` is given it gives
/// the start by the id, and the start's cells are neither read nor compared (the caller
/// compares the whole row). The error names the column at fault (its index) and why: a cell
/// that is not a value of its column, or cells no record is written as (an empty cell a
/// roll always fills, a spin in both forms or neither, a first impact in part).
pub(crate) fn record_from_cells(
    columns: &[&RecordColumn],
    cells: &[Cell<'_>],
    start: Option<&dyn Fn(u64) -> InitialCondition>,
) -> Result<RollRecord, (usize, &'static str)> {
    let mut r = blank();
    let read = |c: &RecordColumn| start.is_none() || !c.of_start();
    for (k, (column, cell)) in columns.iter().zip(cells).enumerate() {
        if read(column) && !matches!(cell, Cell::Empty) {
            (column.set)(&mut r, *cell).ok_or((k, "is not valid"))?;
        }
    }
    if let Some(start) = start {
        r.initial = start(r.id);
    }
    for (k, (column, cell)) in columns.iter().zip(cells).enumerate() {
        if read(column) && !(column.get)(&r).same(*cell) {
            return Err((
                k,
                match cell {
                    Cell::Empty => "is empty, but every roll has one",
                    _ => {
                        "is not one of a record this program writes (a spin in both forms or \
                          neither, or a first impact in part)"
                    }
                },
            ));
        }
    }
    Ok(r)
}

/// The checks of records read back from a file, for one setup: what is fixed for the setup
/// (its body's placement, its clock, its step limit) is worked out once, not per record.
pub struct RecordCheck {
    params: Params,
    placement: Placement,
    clock: StepClock,
    max_steps: u64,
}

impl RecordCheck {
    /// The checks of records of `params` (valid parameters).
    pub fn new(params: &Params) -> RecordCheck {
        RecordCheck {
            params: *params,
            placement: Placement::new(params),
            clock: StepClock::new(params.integrator.dt),
            max_steps: params.max_steps(),
        }
    }

    /// The clock that prints the records' times.
    pub fn clock(&self) -> &StepClock {
        &self.clock
    }

    /// The numbers the setup's die shows ([`Die::face_numbers`](dicesim_physics::Die::face_numbers)).
    pub fn numbers(&self) -> &'static [u8] {
        self.params.die.face_numbers()
    }

    /// Whether a roll of the setup's die can show `face`.
    pub fn is_face(&self, face: u8) -> bool {
        self.numbers().contains(&face)
    }

    /// The refusal of `face` in column `column`, a number the die does not show.
    pub(crate) fn not_a_face(&self, column: &str, face: u8) -> String {
        format!(
            "{column} {face} is not a face of this die (its faces read {})",
            numbers_words(self.numbers())
        )
    }

    /// The face most nearly up at t = 0 of a roll from `initial`, placed exactly as
    /// [`roll_record`](crate::roll_record) places it (a loaded die's corners about its
    /// centre of mass included).
    pub fn start_face(&self, initial: &InitialCondition) -> u8 {
        match self.params.die.is_polyhedral() {
            // A polyhedral die's body is made from its setup: as the roll places it.
            true => lanes::start_face(&self.params, initial),
            false => face_most_nearly_up(&self.placement.start_offsets(initial)),
        }
    }

    /// Checks every field of a record read back from a file against what a roll of the
    /// setup can produce: a start inside the allowed ranges and clear of the table, and each
    /// column's own check ([`COLUMNS`]): the start face that start gives, a face only for a
    /// settled roll, a step count within `integrator.max_time`, the time those steps print,
    /// the impacts. `drawn` is the start the sweep's seed gives this id (random sweeps),
    /// which the record must carry bit for bit. What cannot be checked without rolling again
    /// is the outcome itself (`merge --verify`).
    pub fn check(&self, r: &RollRecord, drawn: Option<&InitialCondition>) -> Result<(), String> {
        let ic = &r.initial;
        match drawn {
            Some(d) if !same_start(ic, d) => {
                return Err(format!(
                    "roll {}: its start is not the one the sweep's seed draws for it (a record of another sweep, or an edited one)",
                    r.id
                ));
            }
            // A draw lies in the sweep's ranges, which were checked clear of the table once.
            Some(_) => {}
            None => ic
                .validate()
                .and_then(|()| self.placement.check_clear_of_table(ic))
                .map_err(|e| format!("roll {}: {e}", r.id))?,
        }
        self.check_ending(r)
    }

    /// The checks of [`RecordCheck::check`] that do not look at the start's values: every
    /// column's own.
    pub fn check_ending(&self, r: &RollRecord) -> Result<(), String> {
        self.check_columns(r, |_| true)
            .map_err(|e| format!("roll {}: {e}", r.id))
    }

    /// Checks an outcome read back from a file: the checks of the columns of a roll's ending
    /// (a face only for a settled roll, a step count within `integrator.max_time`, a timeout
    /// exactly at it, the time those steps print bit for bit, the impacts).
    pub fn check_outcome(&self, o: &Outcome) -> Result<(), String> {
        let r = RollRecord {
            outcome: *o,
            ..blank()
        };
        self.check_columns(&r, |c| c.stage == Stage::Ending)
    }

    fn check_columns(&self, r: &RollRecord, which: fn(&RecordColumn) -> bool) -> Result<(), String> {
        (COLUMNS.iter().filter(|c| which(c)))
            .filter_map(|c| c.check)
            .try_for_each(|check| check(self, r))
    }

    /// Checks that `time_s`, the time of column `name`, is `steps` steps of Δt as printed.
    fn steps_time(&self, name: &str, steps: u64, time_s: f64) -> Result<(), String> {
        let expected = self.clock.time_s(steps);
        match time_s.to_bits() == expected.to_bits() {
            true => Ok(()),
            false => Err(format!(
                "{name} {time_s:?} is not {steps} steps of {} s ({expected:?})",
                self.params.integrator.dt
            )),
        }
    }
}

/// Whether two starts are the same bit for bit (`-0.0` and `0.0` differ, as in a file);
/// where the angular momentum is set it is the spin, and the angular velocity (which a
/// file then leaves empty) is not compared.
pub(crate) fn same_start(a: &InitialCondition, b: &InitialCondition) -> bool {
    let (a, b) = (
        RollRecord {
            initial: *a,
            ..blank()
        },
        RollRecord {
            initial: *b,
            ..blank()
        },
    );
    (COLUMNS.iter().filter(|c| c.of_start())).all(|c| (c.get)(&a).same((c.get)(&b)))
}

/// Whether two records are the same bit for bit, in every column.
pub fn same_record(a: &RollRecord, b: &RollRecord) -> bool {
    COLUMNS.iter().all(|c| (c.get)(a).same((c.get)(b)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::roll_record;

    #[test]
    fn a_record_reports_its_time_as_steps_of_dt_and_its_checks_hold_it_to_that() {
        let params = Params::default();
        let r = roll_record(&params, &InitialCondition::default(), 0);
        let dt = params.integrator.dt;
        // The decimal steps × Δt (Δt = 0.001 s: the steps in thousandths), which the
        // clock's sum of Δt misses in its last bits.
        assert_eq!(dt, 0.001);
        let steps = r.outcome.steps;
        let decimal = format!("{}.{:03}", steps / 1000, steps % 1000);
        assert_eq!(r.outcome.time_s, decimal.parse::<f64>().unwrap());
        let check = RecordCheck::new(&params);
        assert_eq!(check.check(&r, None), Ok(()));
        assert_eq!(check.check(&r, Some(&r.initial)), Ok(()));
        assert_eq!(check.start_face(&r.initial), r.start_face);
        let mut summed = r;
        summed.outcome.time_s = (0..r.outcome.steps).fold(0.0, |t, _| t + dt);
        if summed.outcome.time_s != r.outcome.time_s {
            assert!(
                check
                    .check(&summed, None)
                    .unwrap_err()
                    .contains("steps of 0.001 s")
            );
        }
        let mut turned = r;
        turned.start_face = 7 - r.start_face;
        assert!(
            check
                .check(&turned, None)
                .unwrap_err()
                .starts_with("roll 0: start_face")
        );
        let mut other = r.initial;
        other.height += 1.0;
        assert!(
            check
                .check(&r, Some(&other))
                .unwrap_err()
                .contains("not the one the sweep's seed draws")
        );
    }

    #[test]
    fn a_records_impacts_are_checked_as_read_back() {
        let params = Params::default();
        let r = roll_record(&params, &InitialCondition::default(), 0);
        let check = RecordCheck::new(&params);
        // The paper's throw falls 14 cm before it first touches: it has impacts, the first
        // a whole number of steps into the roll and printed as those steps of Δt.
        let first = r.outcome.first_impact.expect("the paper's throw lands");
        assert!(r.outcome.impacts >= 1 && first.step < r.outcome.steps);
        assert_eq!(
            first.time_s,
            StepClock::new(params.integrator.dt).time_s(first.step)
        );
        let refused = |edit: &dyn Fn(&mut Outcome), words: &str| {
            let mut bad = r;
            edit(&mut bad.outcome);
            let e = check.check(&bad, None).unwrap_err();
            assert!(e.contains(words), "{e}");
        };
        refused(&|o| o.first_impact = None, "impacts but no first impact");
        refused(&|o| o.impacts = 0, "a first impact with 0 impacts");
        refused(
            &|o| o.first_impact.as_mut().unwrap().step = o.steps + 1,
            "outside the roll's steps",
        );
        refused(&|o| o.first_impact.as_mut().unwrap().time_s += 1e-9, "is not");
        refused(
            &|o| o.first_impact.as_mut().unwrap().face_down = 7,
            "first_impact_face_down 7 is not a face of this die (its faces read 1–6)",
        );
        refused(&|o| o.impacts = o.steps, "each needs a step clear of the table");
    }
}

/// The table is the one place a column is stated: every row of it is in the CSV's header and
/// its sidecar's types, the Parquet schema and `batch --versus`'s file (an ending's twice),
/// reads back from both files, and is compared by `same_record`. A row added to the table is
/// held by this test with no change to it.
#[cfg(test)]
mod every_row {
    use super::*;
    use crate::record::roll_record;

    #[test]
    fn every_row_is_in_every_file_and_every_comparison() {
        let params = Params::default();
        let spun = InitialCondition {
            angular_momentum: Some([1.5, -2.0, 0.25]),
            ..InitialCondition::default()
        };
        let records = [
            roll_record(&params, &InitialCondition::default(), 0),
            roll_record(&params, &spun, 1),
        ];
        let spin = SpinColumns::Both;
        let sidecar = records_columns(spin);
        let versus = crate::batch_sweep::versus_columns(spin);
        let mut parquet = crate::parquet::RecordsWriter::new(Vec::new(), spin, "{}").unwrap();
        for r in &records {
            parquet.write(r).unwrap();
        }
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("r.parquet");
        std::fs::write(&path, parquet.finish().unwrap()).unwrap();
        let mut from_parquet = Vec::new();
        crate::parquet::read_records(std::fs::File::open(&path).unwrap(), None, Some(spin), &mut |r| {
            from_parquet.push(r);
            Ok(())
        })
        .unwrap();
        assert_eq!(from_parquet.len(), records.len());
        for (k, column) in COLUMNS.iter().enumerate() {
            let name = column.name();
            assert_eq!(sidecar[k].name, name);
            assert_eq!(sidecar[k].kind, column.ty.kind(), "{name}");
            let named = [name.to_string(), format!("a_{name}"), format!("b_{name}")];
            let sides = versus.iter().filter(|c| named.contains(&c.name)).count();
            assert_eq!(sides, if column.stage == Stage::Ending { 2 } else { 1 }, "{name}");
            for (r, back) in records.iter().zip(&from_parquet) {
                let line = crate::ics::record_csv_line(r, spin);
                let from_csv = crate::ics::parse_record_line(&line, spin).unwrap();
                for read in [&from_csv, back] {
                    assert!(
                        (column.get)(read).same((column.get)(r)),
                        "{name} of roll {}",
                        r.id
                    );
                }
            }
            // A record that differs in this column alone is another record.
            let (r, o) = (&records[0], &records[1]);
            let mut changed = *r;
            if !matches!((column.get)(o), Cell::Empty)
                && (column.set)(&mut changed, (column.get)(o)).is_some()
                && !(column.get)(&changed).same((column.get)(r))
            {
                assert!(!same_record(r, &changed), "{name}");
            }
        }
    }
}
