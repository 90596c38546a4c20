//! The historical dice experiments the model is held against, read from the plain CSV files
//! in the repository's `data/` folder (embedded in the binary, so an installed program has
//! them too). Each file's `#` lines name its source and units; see `docs/real-dice.md`.

use serde::Serialize;

/// The files as shipped.
const WELDON_CSV: &str = include_str!("../data/weldon.csv");
const WOLF_CSV: &str = include_str!("../data/wolf.csv");
const BUDDEN_CSV: &str = include_str!("../data/budden.csv");
const SHAVED_DIE_CSV: &str = include_str!("../data/shaved-die.csv");

/// The faces that count as a success in Weldon's protocol: a 5 or a 6.
const WELDON_FACES: [u8; 2] = [5, 6];

/// Dice thrown at once in Weldon's protocol.
pub(crate) const WELDON_DICE: usize = 12;

/// An experiment that counted faces of cubic dice: what [`crate::compare`] can
/// throw today. (Budden's cuboids need bodies of other proportions: see [`budden`].)
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Dataset {
    /// Weldon's 26 306 throws of 12 dice, counted by the number of 5s and 6s.
    Weldon,
    /// Wolf's red die, 20 000 throws by face.
    WolfRed,
    /// Wolf's white die, 20 000 throws by face.
    WolfWhite,
}

/// A dataset's counts by category, as the file gives them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CountData {
    pub dataset: Experiment,
    /// Who counted, and where it was published (the file's header, joined).
    pub source: String,
    /// The categories' names, in the file's order (`"0"`..`"12"`, or faces `"1"`..`"6"`).
    pub categories: Vec<String>,
    /// Throws counted in each category.
    pub counts: Vec<u64>,
}

/// `x` to the power `n` as `n` multiplications, left to right: the same bits in every build.
/// (`powi` is not: an optimiser that unrolls a loop of constant powers folds them with the
/// compiler's own `pow`, so a release build and a test build would print different χ².)
fn power(x: f64, n: u64) -> f64 {
    (0..n).fold(1.0, |p, _| p * x)
}

impl Dataset {
    pub const ALL: [Dataset; 3] = [Dataset::Weldon, Dataset::WolfRed, Dataset::WolfWhite];

    /// The name on the command line and in files.
    pub fn name(self) -> &'static str {
        match self {
            Dataset::Weldon => "weldon",
            Dataset::WolfRed => "wolf-red",
            Dataset::WolfWhite => "wolf-white",
        }
    }

    /// What one category counts, for table headings.
    pub fn category_words(self) -> &'static str {
        match self {
            Dataset::Weldon => "5s and 6s of 12 dice",
            Dataset::WolfRed | Dataset::WolfWhite => "face",
        }
    }

    /// Dice rolled for one throw of the experiment.
    pub fn dice_per_throw(self) -> usize {
        match self {
            Dataset::Weldon => WELDON_DICE,
            Dataset::WolfRed | Dataset::WolfWhite => 1,
        }
    }

    /// The category of one throw from its dice's faces (1..6 each).
    pub(crate) fn category(self, faces: &[u8]) -> usize {
        match self {
            Dataset::Weldon => faces.iter().filter(|f| WELDON_FACES.contains(f)).count(),
            Dataset::WolfRed | Dataset::WolfWhite => usize::from(faces[0]) - 1,
        }
    }

    /// The probabilities of the categories for a fair die: Binomial(12, 1/3) for Weldon,
    /// 1/6 a face for Wolf's dice.
    pub fn fair_probabilities(self) -> Vec<f64> {
        match self {
            Dataset::Weldon => {
                let n = WELDON_DICE as u64;
                (0..=n)
                    .map(|k| {
                        let ways = (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64);
                        ways * power(1.0 / 3.0, k) * power(2.0 / 3.0, n - k)
                    })
                    .collect()
            }
            Dataset::WolfRed | Dataset::WolfWhite => vec![1.0 / 6.0; 6],
        }
    }

    /// The bundled counts.
    pub fn data(self) -> CountData {
        let (text, column) = match self {
            Dataset::Weldon => (WELDON_CSV, "throws"),
            Dataset::WolfRed => (WOLF_CSV, "red"),
            Dataset::WolfWhite => (WOLF_CSV, "white"),
        };
        let table = Table::parse(text).expect("the bundled data files parse (tested)");
        let counts = table.column(column).iter().map(|&x| x as u64).collect::<Vec<_>>();
        CountData {
            dataset: Experiment::Historical(self),
            source: table.source,
            categories: table.rows.iter().map(|r| r.0.clone()).collect(),
            counts,
        }
    }
}

/// What a comparison's counts are: a historical experiment's, thrown by its protocol, or a
/// player's own counts of one die, thrown once a throw ([`crate::player_counts`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Experiment {
    Historical(Dataset),
    /// A player's die, showing these numbers (in the die's order).
    Player {
        numbers: &'static [u8],
    },
}

impl Experiment {
    /// The name in files: the dataset's, or `counts`.
    pub fn name(self) -> &'static str {
        match self {
            Experiment::Historical(d) => d.name(),
            Experiment::Player { .. } => "counts",
        }
    }

    /// What one category counts, for table headings.
    pub fn category_words(self) -> &'static str {
        match self {
            Experiment::Historical(d) => d.category_words(),
            Experiment::Player { .. } => "face",
        }
    }

    /// Dice rolled for one throw.
    pub fn dice_per_throw(self) -> usize {
        match self {
            Experiment::Historical(d) => d.dice_per_throw(),
            Experiment::Player { .. } => 1,
        }
    }

    /// The category of one throw from its dice's faces (the numbers a player reads).
    pub(crate) fn category(self, faces: &[u8]) -> usize {
        match self {
            Experiment::Historical(d) => d.category(faces),
            Experiment::Player { numbers } => numbers
                .iter()
                .position(|&n| n == faces[0])
                .expect("a die's reading is one of its numbers"),
        }
    }

    /// The probabilities of the categories for a fair die.
    pub fn fair_probabilities(self) -> Vec<f64> {
        match self {
            Experiment::Historical(d) => d.fair_probabilities(),
            Experiment::Player { numbers } => vec![1.0 / numbers.len() as f64; numbers.len()],
        }
    }
}

/// As its name, so a comparison's JSON reads `"dataset": "weldon"` or `"counts"`.
impl Serialize for Experiment {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl CountData {
    pub fn total(&self) -> u64 {
        self.counts.iter().sum()
    }
}

/// One ratio of Budden's cuboids.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BuddenRow {
    /// Length between the square faces over their side, x / y.
    pub ratio: f64,
    /// The published share of throws on a square face (three decimals).
    pub square_share: f64,
    pub throws: u64,
}

impl BuddenRow {
    /// The throws on a square face: the one whole count whose share rounds to the published
    /// one (unique for every row: tested).
    pub fn square_count(&self) -> u64 {
        (self.square_share * self.throws as f64).round() as u64
    }
}

/// Budden's cuboids, by ratio, and the file's source lines.
pub fn budden() -> (Vec<BuddenRow>, String) {
    let table = Table::parse(BUDDEN_CSV).expect("the bundled data files parse (tested)");
    let rows = table
        .rows
        .iter()
        .map(|(ratio, values)| BuddenRow {
            ratio: ratio.parse().expect("numeric ratios (tested)"),
            square_share: values[0],
            throws: values[1] as u64,
        })
        .collect();
    (rows, table.source)
}

/// One cut of the shaved die.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ShavedRow {
    /// The fraction of the side cut off along the 1–6 axis.
    pub cut: f64,
    /// The reported bias `b = 3·P(1 or 6) − 1` (two decimals).
    pub bias: f64,
    pub rolls: u64,
}

impl ShavedRow {
    /// The rolls on 1 or 6 behind the reported bias: `(1 + b)/3` of them, rounded.
    pub fn one_or_six(&self) -> u64 {
        ((1.0 + self.bias) / 3.0 * self.rolls as f64).round() as u64
    }
}

/// The shaved die's cuts, and the file's source lines.
pub fn shaved_die() -> (Vec<ShavedRow>, String) {
    let table = Table::parse(SHAVED_DIE_CSV).expect("the bundled data files parse (tested)");
    let rows = table
        .rows
        .iter()
        .map(|(cut, values)| ShavedRow {
            cut: cut.parse().expect("numeric cuts (tested)"),
            bias: values[0],
            rolls: values[1] as u64,
        })
        .collect();
    (rows, table.source)
}

/// A data file: `#` lines (the source), a header, then rows of a name and numbers.
struct Table {
    source: String,
    header: Vec<String>,
    rows: Vec<(String, Vec<f64>)>,
}

impl Table {
    fn parse(text: &str) -> Result<Table, String> {
        let source = text
            .lines()
            .filter_map(|l| l.strip_prefix('#'))
            .map(str::trim)
            .collect::<Vec<_>>()
            .join(" ");
        let mut reader = csv::ReaderBuilder::new()
            .comment(Some(b'#'))
            .from_reader(text.as_bytes());
        let header = reader
            .headers()
            .map_err(|e| e.to_string())?
            .iter()
            .map(str::to_string)
            .collect::<Vec<_>>();
        let mut rows = Vec::new();
        for (i, record) in reader.records().enumerate() {
            let record = record.map_err(|e| e.to_string())?;
            let values = record
                .iter()
                .skip(1)
                .map(|v| {
                    v.parse::<f64>()
                        .map_err(|_| format!("row {}: `{v}` is not a number", i + 1))
                })
                .collect::<Result<Vec<_>, _>>()?;
            rows.push((record[0].to_string(), values));
        }
        Ok(Table { source, header, rows })
    }

    fn column(&self, name: &str) -> Vec<f64> {
        let i = self
            .header
            .iter()
            .position(|h| h == name)
            .expect("the bundled files have their columns (tested)");
        self.rows.iter().map(|r| r.1[i - 1]).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_file_parses_and_names_its_source() {
        for text in [WELDON_CSV, WOLF_CSV, BUDDEN_CSV, SHAVED_DIE_CSV] {
            let t = Table::parse(text).unwrap();
            assert!(t.source.len() > 100, "{}", t.source);
            assert!(t.rows.iter().all(|r| r.1.len() == t.header.len() - 1));
        }
        for d in Dataset::ALL {
            let data = d.data();
            assert_eq!(data.categories.len(), data.counts.len());
            assert_eq!(d.fair_probabilities().len(), data.counts.len());
        }
    }

    #[test]
    fn the_counts_are_the_published_ones() {
        // The lists, typed again here rather than read from the files.
        let weldon = Dataset::Weldon.data();
        assert_eq!(
            weldon.counts,
            [185, 1149, 3265, 5475, 6114, 5194, 3067, 1331, 403, 105, 14, 4, 0]
        );
        assert_eq!(weldon.total(), 26_306);
        assert_eq!(
            Dataset::WolfRed.data().counts,
            [3407, 3631, 3176, 2916, 3448, 3422]
        );
        assert_eq!(
            Dataset::WolfWhite.data().counts,
            [3246, 3449, 2897, 2841, 3635, 3932]
        );
        assert_eq!(Dataset::WolfRed.data().total(), 20_000);
        assert_eq!(Dataset::WolfWhite.data().total(), 20_000);
        let (rows, source) = budden();
        assert!(source.contains("Mungan"), "{source}");
        assert_eq!(rows.len(), 15);
        assert_eq!(
            (rows[0].ratio, rows[0].square_share, rows[0].throws),
            (0.47, 0.916, 332)
        );
        assert_eq!(
            (rows[14].ratio, rows[14].square_share, rows[14].throws),
            (2.65, 0.006, 503)
        );
        assert_eq!(rows.iter().map(|r| r.throws).sum::<u64>(), 9329);
        // The shaved die: b ≈ 0.06 at a 3 % cut over 36 000 rolls, so 1 or 6 came up
        // (1 + 0.06)/3 · 36 000 = 12 720 times.
        let (cuts, source) = shaved_die();
        assert!(
            source.contains("Murray") && source.contains("plexiglass"),
            "{source}"
        );
        assert_eq!(
            cuts,
            [ShavedRow {
                cut: 0.03,
                bias: 0.06,
                rolls: 36_000
            }]
        );
        assert_eq!(cuts[0].one_or_six(), 12_720);
    }

    #[test]
    fn budden_counts_are_the_one_whole_number_behind_each_share() {
        for row in budden().0 {
            let n = row.throws;
            let matches: Vec<u64> = (0..=n)
                .filter(|&k| ((k as f64 / n as f64) * 1000.0).round() / 1000.0 == row.square_share)
                .collect();
            assert_eq!(matches, [row.square_count()], "ratio {}", row.ratio);
        }
    }

    #[test]
    fn categories_by_protocol() {
        assert_eq!(Dataset::Weldon.category(&[5, 6, 1, 2, 3, 4, 5, 6, 6, 1, 1, 1]), 5);
        assert_eq!(Dataset::WolfRed.category(&[1]), 0);
        assert_eq!(Dataset::WolfWhite.category(&[6]), 5);
        // Binomial(12, 1/3) by its closed form at two points: (2/3)¹² and 12·(1/3)¹¹·(2/3).
        let p = Dataset::Weldon.fair_probabilities();
        assert!((p[0] - (2.0f64 / 3.0).powi(12)).abs() < 1e-15);
        assert!((p[11] - 24.0 / 3f64.powi(12)).abs() < 1e-15);
        assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    }
}
