//! Every key of the explorer as one table row: which mode, which keys, what it does, its
//! footer hint and its help text. Dispatch ([`read`]), the footer, the help overlay and the
//! key tables of docs/explorer.md are all read from [`BINDINGS`], so a key is changed in one place;
//! this is the one module that looks at key codes.

use ratatui::crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

/// Where a binding applies: a screen, or what is on top of it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Scope {
    /// The main screen: the die, its energy and the outcome table.
    Die,
    /// The basin-map screen (`Tab`).
    Map,
    /// Both screens (rows only; a mode is never `Both`).
    Both,
    /// The presentation view (`P`): the die screen's keys work in it too, besides its own.
    Show,
    /// The help overlay (`?`).
    Help,
    /// A yes/no question (quit, reset, load over unsaved changes).
    Prompt,
    /// Typing text: a value, the batch size, ε, a map range; the save dialog's fields too.
    Text,
    /// The save dialog: its two text fields.
    Save,
    /// The preset picker (`o`).
    Picker,
    /// Throw mode (`f`): a drag on the die, or the aiming keys, throws it.
    Throw,
}

impl Scope {
    /// Whether a row of `self` applies in mode `on`.
    pub(crate) fn includes(self, on: Scope) -> bool {
        self == on
            || (self == Both && matches!(on, Die | Map | Show))
            || (self == Die && on == Show)
            || (self == Text && on == Save)
    }

    /// Every mode, for the checks that hold in all of them.
    pub(crate) const MODES: [Scope; 9] = [Die, Map, Show, Help, Prompt, Text, Save, Picker, Throw];

    /// How the help and the README title this mode's keys.
    pub(crate) fn title(self) -> &'static str {
        match self {
            Die | Both => "Keys",
            Map => "Basin-map screen keys",
            Show => "Presentation view keys (the main screen's work too)",
            Help => "In the help",
            Prompt => "Answering a question",
            Text => "Typing a value, a range or a name",
            Save => "The save dialog",
            Picker => "The preset picker",
            Throw => "Throwing by hand (f)",
        }
    }

    /// Whether printable characters are text here rather than keys.
    pub(crate) fn takes_text(self) -> bool {
        matches!(self, Text | Save)
    }
}

/// What a key does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Action {
    TogglePlay,
    StepForward,
    StepBack,
    ToStart,
    ToEnd,
    /// To the next impact ([`dicesim_physics::Impacts`]), computing on if need be.
    NextImpact,
    PreviousImpact,
    /// To the step at which the stopping rule decided the face.
    ToDecided,
    Replay,
    RandomRoll,
    Batch,
    BatchSize,
    ClearTable,
    Slower,
    Faster,
    SelectPrevious,
    SelectNext,
    SelectFirst,
    SelectLast,
    Decrease,
    Increase,
    DecreaseBig,
    IncreaseBig,
    TypeValue,
    LogScale,
    PlotQuantity,
    PhasePlot,
    /// The plot's value axis from zero, or fitted to the curves.
    FitAxis,
    /// A second quantity on the plot, sharing its axis (the same unit).
    SecondQuantity,
    /// A face pair coloured and its body axis drawn.
    FacePair,
    /// Throw mode on.
    ThrowMode,
    Export,
    ExportAnimation,
    Arrows,
    Twin,
    TwinEpsilonDown,
    TwinEpsilonUp,
    TwinEpsilonType,
    Differ,
    Theme,
    Drawing,
    OrbitLeft,
    OrbitRight,
    TiltUp,
    TiltDown,
    ZoomIn,
    ZoomOut,
    ResetCamera,
    OpenPreset,
    SavePreset,
    ResetSetup,
    OpenMap,
    /// The presentation view on or off.
    Presentation,
    /// The presentation view's number: the next of height, speed, spin, kinetic energy.
    NextReadout,
    /// The lesson's next step (or, its card up, the screen under the card).
    NextStep,
    /// The lesson's step before.
    PreviousStep,
    Help,
    Close,
    Quit,
    // The basin-map screen's own.
    MapBack,
    CursorLeft,
    CursorRight,
    CursorUp,
    CursorDown,
    CursorLeftBig,
    CursorRightBig,
    CursorUpBig,
    CursorDownBig,
    ReplayCell,
    MapZoomIn,
    MapZoomOut,
    NextXAxis,
    NextYAxis,
    TypeXRange,
    TypeYRange,
    MapLayer,
    ExportMap,
    MapExportSize,
    // Throw mode's own: where the die is grabbed.
    GrabLeft,
    GrabRight,
    GrabUp,
    GrabDown,
    // Questions, dialogs and text entry.
    /// Yes / apply / open.
    Confirm,
    /// Text entry: delete the last character.
    Delete,
    /// The save dialog: the other field.
    NextField,
}

/// One row of the key table.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Binding {
    pub(crate) screen: Scope,
    pub(crate) keys: &'static [KeyCode],
    /// How the keys are written in the help and the README (space-separated).
    pub(crate) label: &'static str,
    pub(crate) action: Action,
    /// The footer's words and priority (on a narrow terminal the highest go first, 0
    /// stays); `None` for keys only the help lists.
    pub(crate) hint: Option<Hint>,
    pub(crate) help: &'static str,
}

/// A footer hint: the keys as the footer writes them, what they do, how soon to drop it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Hint {
    pub(crate) keys: &'static str,
    pub(crate) words: &'static str,
    pub(crate) priority: u8,
}

const fn hint(keys: &'static str, words: &'static str, priority: u8) -> Option<Hint> {
    Some(Hint {
        keys,
        words,
        priority,
    })
}

use Action as A;
use KeyCode as K;
use Scope::{Both, Die, Help, Map, Picker, Prompt, Save, Show, Text, Throw};

macro_rules! row {
    ($screen:expr, [$($key:expr),+], $label:expr, $action:expr, $hint:expr, $help:expr) => {
        Binding {
            screen: $screen,
            keys: &[$($key),+],
            label: $label,
            action: $action,
            hint: $hint,
            help: $help,
        }
    };
}

/// The key table, in the order the help and the README list it.
pub(crate) const BINDINGS: &[Binding] = &[
    row!(
        Die,
        [K::Char(' ')],
        "space",
        A::TogglePlay,
        hint("space", "play", 0),
        "play / pause, on from wherever the roll is (at its end: watch it again)"
    ),
    row!(
        Die,
        [K::Char('.'), K::Char('n')],
        ". n",
        A::StepForward,
        hint(", .", "step", 1),
        "one step of Δt forward, then pause"
    ),
    row!(
        Die,
        [K::Char(',')],
        ",",
        A::StepBack,
        None,
        "one step of Δt back, then pause"
    ),
    row!(
        Die,
        [K::Home],
        "Home",
        A::ToStart,
        hint("Home End", "start/end", 4),
        "jump to the start of the roll; a click on the timeline under the die jumps there"
    ),
    row!(
        Die,
        [K::End],
        "End",
        A::ToEnd,
        None,
        "jump to the end of the roll (computing it if it has not got there yet)"
    ),
    row!(
        Die,
        [K::Char('i')],
        "i",
        A::NextImpact,
        hint("i I F", "impacts", 2),
        "jump to the next impact, the step its contact begins (the first in contact after the die was clear of \
         the table; ┃ on the timeline), computing on if need be"
    ),
    row!(
        Die,
        [K::Char('I')],
        "I",
        A::PreviousImpact,
        None,
        "jump back to the previous impact"
    ),
    row!(
        Die,
        [K::Char('F')],
        "F",
        A::ToDecided,
        None,
        "jump to the step where the face was decided (✓ on the timeline), computing on if need be"
    ),
    row!(
        Die,
        [K::Char('r')],
        "r",
        A::Replay,
        hint("r", "replay", 2),
        "replay the same start: the same face, every time"
    ),
    row!(
        Die,
        [K::Char('R')],
        "R",
        A::RandomRoll,
        hint("R", "random", 2),
        "a random roll from the preset's ranges (counted in the table)"
    ),
    row!(
        Die,
        [K::Char('b')],
        "b",
        A::Batch,
        hint("b", "batch", 1),
        "a batch of random rolls into the table, with a progress gauge; b again cancels"
    ),
    row!(
        Die,
        [K::Char('B')],
        "B",
        A::BatchSize,
        hint("B", "size", 4),
        "the batch size: 1 000 → 10 000 → 100 000 → type one (1 … 10 000 000)"
    ),
    row!(
        Die,
        [K::Char('c')],
        "c",
        A::ClearTable,
        None,
        "clear the outcome table"
    ),
    row!(
        Die,
        [K::Char('['), K::Char('-')],
        "[ -",
        A::Slower,
        hint("[ ]", "speed", 1),
        "slower: 1/100× … 100×, then instant"
    ),
    row!(
        Die,
        [K::Char(']'), K::Char('+'), K::Char('=')],
        "] +",
        A::Faster,
        None,
        "faster"
    ),
    row!(
        Die,
        [K::Up, K::Char('k')],
        "↑ k",
        A::SelectPrevious,
        hint("↑↓←→", "values", 3),
        "select the value above"
    ),
    row!(
        Die,
        [K::Down, K::Char('j')],
        "↓ j",
        A::SelectNext,
        None,
        "select the value below"
    ),
    row!(
        Die,
        [K::Char('g')],
        "g",
        A::SelectFirst,
        None,
        "select the first value"
    ),
    row!(
        Die,
        [K::Char('G')],
        "G",
        A::SelectLast,
        None,
        "select the last value"
    ),
    row!(
        Die,
        [K::Left, K::Char('h')],
        "← h",
        A::Decrease,
        None,
        "lower the value (Shift: big steps); ground values act at once, others restart the roll"
    ),
    row!(
        Die,
        [K::Right, K::Char('l')],
        "→ l",
        A::Increase,
        None,
        "raise the value (Shift: big steps)"
    ),
    row!(
        Die,
        [K::Char('H')],
        "H",
        A::DecreaseBig,
        None,
        "lower the value in a big step"
    ),
    row!(
        Die,
        [K::Char('L')],
        "L",
        A::IncreaseBig,
        None,
        "raise the value in a big step"
    ),
    row!(
        Die,
        [K::Enter],
        "Enter",
        A::TypeValue,
        None,
        "type an exact value (checked against its range; Esc cancels); a digit starts it typed"
    ),
    row!(
        Die,
        [K::Char('p')],
        "p",
        A::LogScale,
        None,
        "energy plot: linear / log scale"
    ),
    row!(
        Die,
        [K::Char('w')],
        "w",
        A::PlotQuantity,
        hint("w V", "plot", 3),
        "plot: the energy terms → height → lowest corner → speed → spin rate → contact force → each \
         energy term → each stability load, against time (│ marks the time on screen); in the phase \
         plot, the quantity up"
    ),
    row!(
        Die,
        [K::Char('V')],
        "V",
        A::PhasePlot,
        None,
        "phase plot on / off: a second quantity (up) against the one plotted (across), ● the state on screen"
    ),
    row!(
        Die,
        [K::Char('y')],
        "y",
        A::FitAxis,
        None,
        "the plot's value axis: the whole roll's, or fitted to the curves around the time on screen (a quarter \
         of the time axis; the rest runs off the plot)"
    ),
    row!(
        Die,
        [K::Char('Y')],
        "Y",
        A::SecondQuantity,
        None,
        "a second curve against time on the same axis: the next quantity with the plot's unit (height and \
         lowest corner, the energy terms, the stability loads), then none"
    ),
    row!(
        Die,
        [K::Char('e')],
        "e",
        A::Export,
        hint("e", "export", 4),
        "export the roll into the current folder: its trace (CSV) and energy plot (PNG); e again cancels"
    ),
    row!(
        Die,
        [K::Char('A')],
        "A",
        A::ExportAnimation,
        None,
        "export the roll as shown as an animated GIF (current folder); A again cancels"
    ),
    row!(
        Die,
        [K::Char('v')],
        "v",
        A::Arrows,
        hint("v", "arrows", 3),
        "arrows: spin ω, angular momentum L, velocity v, contact forces F"
    ),
    row!(
        Die,
        [K::Char('T')],
        "T",
        A::Twin,
        hint("T", "twin", 3),
        "chaos twin: a second die (the ghost) whose height, velocity and spin are × (1 + ε)"
    ),
    row!(
        Die,
        [K::Char('<')],
        "<",
        A::TwinEpsilonDown,
        None,
        "twin: ε ÷10 (down to 1e-15); both dice roll again"
    ),
    row!(
        Die,
        [K::Char('>')],
        ">",
        A::TwinEpsilonUp,
        None,
        "twin: ε ×10 (up to 0.1)"
    ),
    row!(Die, [K::Char('E')], "E", A::TwinEpsilonType, None, "twin: type ε"),
    row!(
        Die,
        [K::Char('D')],
        "D",
        A::Differ,
        hint("D", "differ", 4),
        "parameter twin (differ): the next value changes go to a second die B only, rolled from the \
         same start beside A; D again ends it"
    ),
    row!(
        Die,
        [K::Char('M')],
        "M",
        A::FacePair,
        None,
        "mark a face pair, coloured with its body axis through it: 2 and 5 (the tennis racket's flip) → 1 and \
         6 → 3 and 4 → none"
    ),
    row!(
        Die,
        [K::Char('f')],
        "f",
        A::ThrowMode,
        hint("f", "throw", 2),
        "throw by hand: a drag on the die throws it (its length and direction the velocity, where it starts \
         the spin), or aim with the keys; Ctrl- or Alt-drag throws without it"
    ),
    row!(
        Die,
        [K::Char('t')],
        "t",
        A::Theme,
        None,
        "theme: dark / light / projector (high contrast, bold); NO_COLOR turns colour off"
    ),
    row!(
        Die,
        [K::Char('m')],
        "m",
        A::Drawing,
        None,
        "draw the die with Braille dots / plain ASCII"
    ),
    row!(
        Die,
        [K::Char('a')],
        "a",
        A::OrbitLeft,
        None,
        "orbit the camera left"
    ),
    row!(
        Die,
        [K::Char('d')],
        "d",
        A::OrbitRight,
        None,
        "orbit the camera right"
    ),
    row!(Die, [K::Char('W')], "W", A::TiltUp, None, "tilt the camera up"),
    row!(
        Die,
        [K::Char('S')],
        "S",
        A::TiltDown,
        None,
        "tilt the camera down"
    ),
    row!(
        Die,
        [K::Char('z')],
        "z",
        A::ZoomIn,
        None,
        "zoom in (or scroll on the die; drag it to orbit)"
    ),
    row!(Die, [K::Char('x')], "x", A::ZoomOut, None, "zoom out"),
    row!(Die, [K::Char('C')], "C", A::ResetCamera, None, "reset the camera"),
    row!(
        Die,
        [K::Char('o')],
        "o",
        A::OpenPreset,
        hint("o s", "presets", 4),
        "open a preset (shipped ones and yours, ★); asks first if the setup has unsaved changes"
    ),
    row!(
        Die,
        [K::Char('s')],
        "s",
        A::SavePreset,
        None,
        "save the setup and the view as a preset, with a description (asks before replacing one)"
    ),
    row!(
        Die,
        [K::Backspace],
        "Backspace",
        A::ResetSetup,
        hint("⌫", "reset", 4),
        "reset the setup to the open preset (asks first if it has changes)"
    ),
    row!(
        Die,
        [K::Tab, K::BackTab],
        "Tab",
        A::OpenMap,
        hint("Tab", "map", 2),
        "the basin-map screen"
    ),
    row!(
        Die,
        [K::Char('P')],
        "P",
        A::Presentation,
        hint("P", "present", 2),
        "presentation view: the die large over a height scale, the face up in big digits, the time and one number; P or Esc back"
    ),
    row!(
        Show,
        [K::Char('N')],
        "N",
        A::NextReadout,
        hint("N", "number", 0),
        "the number shown: height → speed → spin → kinetic energy"
    ),
    row!(
        Map,
        [K::Tab, K::BackTab],
        "Tab",
        A::MapBack,
        hint("Tab", "die", 0),
        "back to the die (Esc too)"
    ),
    row!(
        Map,
        [K::Left, K::Char('h')],
        "← h",
        A::CursorLeft,
        hint("←↓↑→", "cursor", 1),
        "move the cursor left (Shift: 8 cells)"
    ),
    row!(
        Map,
        [K::Right, K::Char('l')],
        "→ l",
        A::CursorRight,
        None,
        "move the cursor right"
    ),
    row!(
        Map,
        [K::Up, K::Char('k')],
        "↑ k",
        A::CursorUp,
        None,
        "move the cursor up"
    ),
    row!(
        Map,
        [K::Down, K::Char('j')],
        "↓ j",
        A::CursorDown,
        None,
        "move the cursor down"
    ),
    row!(Map, [K::Char('H')], "H", A::CursorLeftBig, None, "8 cells left"),
    row!(Map, [K::Char('L')], "L", A::CursorRightBig, None, "8 cells right"),
    row!(Map, [K::Char('K')], "K", A::CursorUpBig, None, "8 cells up"),
    row!(Map, [K::Char('J')], "J", A::CursorDownBig, None, "8 cells down"),
    row!(
        Map,
        [K::Enter],
        "Enter",
        A::ReplayCell,
        hint("Enter", "replay", 1),
        "replay the cell under the cursor in the die view"
    ),
    row!(
        Map,
        [K::Char('z')],
        "z",
        A::MapZoomIn,
        hint("z Z", "zoom in/out", 1),
        "zoom in ×4 around the cursor"
    ),
    row!(
        Map,
        [K::Char('Z'), K::Backspace],
        "Z Backspace",
        A::MapZoomOut,
        None,
        "zoom back out"
    ),
    row!(
        Map,
        [K::Char('x')],
        "x",
        A::NextXAxis,
        hint("x y", "axis", 2),
        "next value of the parameter list on the x axis"
    ),
    row!(
        Map,
        [K::Char('y')],
        "y",
        A::NextYAxis,
        None,
        "next value on the y axis"
    ),
    row!(
        Map,
        [K::Char('X')],
        "X",
        A::TypeXRange,
        hint("X Y", "range", 2),
        "type the x range as MIN MAX"
    ),
    row!(
        Map,
        [K::Char('Y')],
        "Y",
        A::TypeYRange,
        None,
        "type the y range as MIN MAX"
    ),
    row!(
        Map,
        [K::Char('v')],
        "v",
        A::MapLayer,
        hint("v", "face/time", 3),
        "colour by face up / by settle time (borders light up)"
    ),
    row!(
        Map,
        [K::Char('e')],
        "e",
        A::ExportMap,
        hint("e", "export PNG", 3),
        "export the map into the current folder: its cells (CSV) and picture (PNG, its setup in a caption and in the file's text); e again cancels"
    ),
    row!(
        Map,
        [K::Char('E')],
        "E",
        A::MapExportSize,
        None,
        "the PNG's size: 1200×800 (screen) → 1920×1280 (slide) → 3000×2000 (print) → 6000×4000 (poster)"
    ),
    row!(
        Both,
        [K::PageDown, K::Char('}')],
        "PageDown }",
        A::NextStep,
        hint("PgDn", "lesson", 1),
        "the lesson: its next step opens its preset with its speed, arrows, plot and screen, its sentence in \
         large type on a card; PageDown again (or any other key) puts the card down; a presenter's clicker sends it"
    ),
    row!(
        Both,
        [K::PageUp, K::Char('{')],
        "PageUp {",
        A::PreviousStep,
        None,
        "the lesson's step before"
    ),
    row!(
        Both,
        [K::Char('?')],
        "?",
        A::Help,
        hint("?", "help", 0),
        "this help (↑↓ scroll, ? or Esc closes)"
    ),
    row!(
        Both,
        [K::Esc],
        "Esc",
        A::Close,
        None,
        "close the topmost thing: an editor, a dialog, the help, the map screen; never quits"
    ),
    row!(
        Both,
        [K::Char('q')],
        "q",
        A::Quit,
        hint("q", "quit", 0),
        "quit (asks first if the setup has unsaved changes: y or q again quits); Ctrl-C quits at once"
    ),
    row!(
        Help,
        [K::Up, K::Char('k')],
        "↑ k",
        A::SelectPrevious,
        hint("↑↓", "scroll", 0),
        "scroll up"
    ),
    row!(
        Help,
        [K::Down, K::Char('j')],
        "↓ j",
        A::SelectNext,
        None,
        "scroll down"
    ),
    row!(
        Help,
        [K::Char('?'), K::Esc, K::Enter, K::Char('q')],
        "? Esc Enter q",
        A::Close,
        hint("? Esc", "close help", 0),
        "close the help"
    ),
    row!(
        Prompt,
        [K::Char('y')],
        "y",
        A::Confirm,
        hint("y", "yes", 0),
        "yes: go ahead"
    ),
    row!(
        Prompt,
        [K::Char('q')],
        "q",
        A::Quit,
        hint("q", "quits", 0),
        "asked whether to quit: quit; asked anything else: no"
    ),
    row!(
        Prompt,
        [K::Backspace],
        "Backspace",
        A::ResetSetup,
        hint("⌫", "resets", 0),
        "asked whether to reset: reset; asked anything else: no"
    ),
    row!(
        Prompt,
        [K::Enter],
        "Enter",
        A::OpenPreset,
        hint("Enter", "opens it", 0),
        "asked whether to open a preset over changes: open it; asked anything else: no"
    ),
    row!(
        Prompt,
        [K::Esc, K::Char('n')],
        "Esc n",
        A::Close,
        None,
        "no: everything stays as it is (so does any other key)"
    ),
    // Before the text rows: the save dialog's footer names its own key first.
    row!(
        Save,
        [K::Tab, K::BackTab, K::Up, K::Down],
        "Tab ↑ ↓",
        A::NextField,
        hint("Tab", "name/description", 0),
        "the other field: name / description"
    ),
    row!(
        Text,
        [K::Enter],
        "Enter",
        A::Confirm,
        hint("Enter", "apply", 0),
        "apply what was typed (an error says why not, and typing goes on)"
    ),
    row!(
        Text,
        [K::Esc],
        "Esc",
        A::Close,
        hint("Esc", "cancel", 0),
        "cancel: nothing changes; every other key (q among them) is typed as text"
    ),
    row!(
        Text,
        [K::Backspace],
        "Backspace",
        A::Delete,
        None,
        "delete the last character"
    ),
    row!(
        Picker,
        [K::Up, K::Char('k')],
        "↑ k",
        A::SelectPrevious,
        hint("↑↓", "choose", 0),
        "the preset above"
    ),
    row!(
        Picker,
        [K::Down, K::Char('j')],
        "↓ j",
        A::SelectNext,
        None,
        "the preset below"
    ),
    row!(
        Picker,
        [K::Home, K::Char('g')],
        "Home g",
        A::SelectFirst,
        None,
        "the first preset"
    ),
    row!(
        Picker,
        [K::End, K::Char('G')],
        "End G",
        A::SelectLast,
        None,
        "the last preset"
    ),
    row!(
        Picker,
        [K::Enter],
        "Enter",
        A::Confirm,
        hint("Enter", "open", 0),
        "open the preset chosen (asks first if the setup has unsaved changes)"
    ),
    row!(
        Picker,
        [K::Esc, K::Char('o'), K::Char('q')],
        "Esc o q",
        A::Close,
        hint("Esc", "close", 0),
        "close the picker"
    ),
    row!(
        Throw,
        [K::Left, K::Char('h')],
        "← h",
        A::CursorLeft,
        hint("←→↑↓", "aim", 0),
        "the throw's end a cell left (Shift: four): from the grab point to it, the velocity across the \
         table (a hundredth of a second to cover it)"
    ),
    row!(
        Throw,
        [K::Right, K::Char('l')],
        "→ l",
        A::CursorRight,
        None,
        "the throw's end a cell right"
    ),
    row!(
        Throw,
        [K::Up, K::Char('k')],
        "↑ k",
        A::CursorUp,
        None,
        "the throw's end a cell up"
    ),
    row!(
        Throw,
        [K::Down, K::Char('j')],
        "↓ j",
        A::CursorDown,
        None,
        "the throw's end a cell down"
    ),
    row!(
        Throw,
        [K::Char('a')],
        "a",
        A::GrabLeft,
        hint("w a s d", "grab point", 1),
        "grab the die a cell further left: off its centre, the throw spins it"
    ),
    row!(
        Throw,
        [K::Char('d')],
        "d",
        A::GrabRight,
        None,
        "grab a cell further right"
    ),
    row!(Throw, [K::Char('w')], "w", A::GrabUp, None, "grab a cell higher"),
    row!(Throw, [K::Char('s')], "s", A::GrabDown, None, "grab a cell lower"),
    row!(
        Throw,
        [K::Enter],
        "Enter",
        A::Confirm,
        hint("Enter", "throw", 0),
        "throw: the velocity and spin go into the parameter list (s saves them) and the die is thrown from its start"
    ),
    row!(
        Throw,
        [K::Backspace],
        "Backspace",
        A::Delete,
        hint("⌫", "unaimed", 2),
        "grab and aim back at the die's centre: no throw"
    ),
    row!(
        Throw,
        [K::Esc, K::Char('f'), K::Char('q')],
        "Esc f q",
        A::Close,
        hint("Esc f", "back", 0),
        "back to the die screen's keys, nothing thrown"
    ),
];

/// What a key press means in a mode.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Input {
    /// A row of the table; `coarse` when Shift, Ctrl or Alt was held (big steps).
    Act { action: Action, coarse: bool },
    /// A character typed as text (or, on the main screen, a digit that starts the editor).
    Type(char),
    /// Ctrl-C: quit at once, in every mode.
    Interrupt,
    /// Nothing in this mode; the footer says so, naming the key.
    Nothing(String),
}

/// What `key` means in `mode`. In text entry every printable character is text unless a
/// row claims its key; on the main screen a digit opens the value editor with it typed.
pub(crate) fn read(mode: Scope, key: KeyEvent) -> Input {
    let ctrl = key.modifiers.contains(KeyModifiers::CONTROL);
    if ctrl && matches!(key.code, K::Char('c') | K::Char('C')) {
        return Input::Interrupt;
    }
    let printable = match key.code {
        K::Char(c) if !c.is_control() && !ctrl && !key.modifiers.contains(KeyModifiers::ALT) => Some(c),
        _ => None,
    };
    if let Some(b) = lookup(mode, key.code) {
        return Input::Act {
            action: b.action,
            coarse: key
                .modifiers
                .intersects(KeyModifiers::SHIFT | KeyModifiers::CONTROL | KeyModifiers::ALT),
        };
    }
    match printable {
        Some(c) if mode.takes_text() => Input::Type(c),
        Some(c) if mode == Die && c.is_ascii_digit() => Input::Type(c),
        _ => Input::Nothing(name(key.code)),
    }
}

/// A key's name as the footer writes it when the key means nothing.
fn name(code: KeyCode) -> String {
    let name = match code {
        K::Char(' ') => "space",
        K::Char(c) => return c.to_string(),
        K::F(_) => "that function key",
        K::Insert => "Insert",
        K::Delete => "Delete",
        K::PageUp => "PageUp",
        K::PageDown => "PageDown",
        K::Left => "←",
        K::Right => "→",
        K::Up => "↑",
        K::Down => "↓",
        K::Home => "Home",
        K::End => "End",
        K::Enter => "Enter",
        K::Tab | K::BackTab => "Tab",
        K::Backspace => "Backspace",
        K::Esc => "Esc",
        _ => "that key",
    };
    name.to_string()
}

/// The keys of `action` in `mode` as the help writes them, for texts that name a key.
pub(crate) fn label(mode: Scope, action: Action) -> &'static str {
    BINDINGS
        .iter()
        .find(|b| b.screen.includes(mode) && b.action == action)
        .map_or("?", |b| b.label)
}

/// How texts name the key that quits in every mode, text entry included ([`Input::Interrupt`]):
/// no row of the table, since no mode may rebind it.
pub(crate) const INTERRUPT: &str = "Ctrl-C";

/// The first key of `action` in `mode`, for a text too short to list them all.
pub(crate) fn first_key(mode: Scope, action: Action) -> &'static str {
    label(mode, action).split(' ').next().unwrap_or("?")
}

/// The keys of several actions in `mode`, as one hint writes them (`T < > E`).
pub(crate) fn labels(mode: Scope, actions: &[Action]) -> String {
    actions
        .iter()
        .map(|&a| label(mode, a))
        .collect::<Vec<_>>()
        .join(" ")
}

/// How a text names the keys of `action` in `mode`: the footer's way when the row has a
/// hint, else the help's, alternatives joined by "or" (`? or Esc`).
pub(crate) fn named(mode: Scope, action: Action) -> String {
    row_of(mode, action).map_or_else(
        || "?".to_string(),
        |b| {
            b.hint
                .map_or(b.label, |h| h.keys)
                .split(' ')
                .collect::<Vec<_>>()
                .join(" or ")
        },
    )
}

/// What the row of `action` in `mode` says it does in the footer.
pub(crate) fn words(mode: Scope, action: Action) -> &'static str {
    row_of(mode, action).and_then(|b| b.hint).map_or("", |h| h.words)
}

fn row_of(mode: Scope, action: Action) -> Option<&'static Binding> {
    BINDINGS
        .iter()
        .find(|b| b.screen.includes(mode) && b.action == action)
}

/// The binding of `code` on `screen`, if any.
pub(crate) fn lookup(screen: Scope, code: KeyCode) -> Option<&'static Binding> {
    BINDINGS
        .iter()
        .find(|b| b.screen.includes(screen) && b.keys.contains(&code))
}

/// Every row that applies on `screen` (its own and the shared ones), for its footer.
pub(crate) fn rows(screen: Scope) -> impl Iterator<Item = &'static Binding> {
    BINDINGS.iter().filter(move |b| b.screen.includes(screen))
}

/// The rows one section of the help and the README lists: the die screen's with the
/// shared ones, every other mode its own.
pub(crate) fn section(screen: Scope) -> impl Iterator<Item = &'static Binding> {
    BINDINGS.iter().filter(move |b| match screen {
        Die => matches!(b.screen, Die | Both),
        _ => b.screen == screen,
    })
}

/// The key tables of the explorer's manual (docs/explorer.md) as they must read: one for the
/// die screen (with the keys of both screens), then one for each other mode. The repository's
/// docs test holds the manual to it.
pub fn markdown_tables() -> String {
    let table = |title: &str, screen: Scope| {
        let mut out = format!("| {title} | |\n|---|---|\n");
        for b in section(screen) {
            let keys: Vec<String> = b.label.split(' ').map(|k| format!("`{k}`")).collect();
            out.push_str(&format!("| {} | {} |\n", keys.join(" "), b.help));
        }
        out
    };
    Scope::MODES
        .iter()
        .map(|&mode| table(mode.title(), mode))
        .collect::<Vec<_>>()
        .join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn press(mode: Scope, code: KeyCode) -> Input {
        read(mode, KeyEvent::new(code, KeyModifiers::NONE))
    }

    #[test]
    fn no_key_means_two_things_in_one_mode() {
        for mode in Scope::MODES {
            let mut seen: Vec<KeyCode> = Vec::new();
            for b in BINDINGS.iter().filter(|b| b.screen.includes(mode)) {
                for k in b.keys {
                    assert!(!seen.contains(k), "{k:?} bound twice in {mode:?}");
                    seen.push(*k);
                }
            }
        }
    }

    #[test]
    fn esc_closes_and_never_quits_q_quits_the_screens_closes_overlays_and_is_text_in_text() {
        let act = |action| Input::Act {
            action,
            coarse: false,
        };
        for mode in Scope::MODES {
            assert_eq!(press(mode, K::Esc), act(A::Close), "Esc in {mode:?}");
            let q = press(mode, K::Char('q'));
            let expected = match mode {
                Die | Map | Show => act(A::Quit),
                // Its own key answers the quit question; in the others it is a no.
                Prompt => act(A::Quit),
                Text | Save => Input::Type('q'),
                _ => act(A::Close),
            };
            assert_eq!(q, expected, "q in {mode:?}");
            let ctrl_c = read(mode, KeyEvent::new(K::Char('c'), KeyModifiers::CONTROL));
            assert_eq!(ctrl_c, Input::Interrupt, "Ctrl-C in {mode:?}");
        }
    }

    #[test]
    fn text_entry_takes_every_printable_character_and_the_main_screen_no_digit() {
        for c in ['q', 'y', '2', ' ', 'é', '?', 'e', '-', 'T'] {
            assert_eq!(press(Text, K::Char(c)), Input::Type(c));
            assert_eq!(press(Save, K::Char(c)), Input::Type(c));
        }
        for d in '0'..='9' {
            assert_eq!(press(Die, K::Char(d)), Input::Type(d), "{d} on the main screen");
            assert!(
                !BINDINGS
                    .iter()
                    .any(|b| b.screen.includes(Die) && b.keys.contains(&K::Char(d))),
                "{d} is bound on the main screen"
            );
        }
        assert_eq!(press(Die, K::Char('u')), Input::Nothing("u".into()));
        assert_eq!(press(Help, K::Char('x')), Input::Nothing("x".into()));
    }
}
