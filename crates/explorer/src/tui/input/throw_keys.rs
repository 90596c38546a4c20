//! Throw mode's keys and the throw gesture (docs/explorer.md, "A throw by hand"). The aim is
//! the state's [`Throw`]; a drag on the die or the aiming keys move it; releasing the drag,
//! or `Enter`, throws: the start's velocity and spin become the throw's and the roll plays
//! from t = 0, so `s` saves the throw and `r` throws it again.

use crate::tui::state::app::App;
use crate::tui::state::projection::{Projection, die_view};
use crate::tui::state::throw::{COARSE_CELLS, Throw, Thrown};
use crate::tui::vocabulary::key_table::{Action, Input, Scope, label};
use crate::tui::vocabulary::solid::inside;

/// The view the die is drawn in on the die screen, where the throw is aimed.
fn view(app: &App) -> Option<Projection> {
    app.areas().map(|a| die_view(app, a.die))
}

/// `f`: throw mode on, aimed at nothing yet.
pub(crate) fn enter(app: &mut App) {
    app.die_screen.throw = Some(Throw::default());
    app.notice = Some(format!(
        "throw mode: drag the die, or aim with the arrows; {} throws, {} goes back",
        label(Scope::Throw, Action::Confirm),
        label(Scope::Throw, Action::Close)
    ));
}

/// A key in throw mode.
pub(crate) fn on_key(app: &mut App, input: &Input) {
    let Input::Act { action, coarse } = *input else {
        app.nothing_here(input);
        return;
    };
    let cells = if coarse { COARSE_CELLS } else { 1.0 };
    let Some(cell) = view(app).map(|v| v.cell_size()) else {
        return;
    };
    let Some(aim) = app.die_screen.throw.as_mut() else {
        return;
    };
    match action {
        Action::CursorLeft => aim.aim(cell, (-cells, 0.0)),
        Action::CursorRight => aim.aim(cell, (cells, 0.0)),
        Action::CursorUp => aim.aim(cell, (0.0, -cells)),
        Action::CursorDown => aim.aim(cell, (0.0, cells)),
        Action::GrabLeft => aim.move_grab(cell, (-1.0, 0.0)),
        Action::GrabRight => aim.move_grab(cell, (1.0, 0.0)),
        Action::GrabUp => aim.move_grab(cell, (0.0, -1.0)),
        Action::GrabDown => aim.move_grab(cell, (0.0, 1.0)),
        Action::Delete => *aim = Throw::default(),
        Action::Confirm => throw(app),
        Action::Close => app.die_screen.throw = None,
        _ => {}
    }
}

/// A press at a cell of the screen: on the die, it grabs the die there and a drag begins;
/// `passing` (Ctrl or Alt held outside throw mode) ends throw mode with the drag. Whether
/// it grabbed.
pub(crate) fn press(app: &mut App, column: u16, row: u16, passing: bool) -> bool {
    let Some(view) = view(app) else { return false };
    let area = view.area;
    if !(area.x..area.right()).contains(&column) || !(area.y..area.bottom()).contains(&row) {
        return false;
    }
    let at = view.centre_of(column - area.x, row - area.y);
    let die = &app.roll.live.die;
    let outline = crate::tui::panels::die::body_of(app, die).outline(|p| view.flat(p));
    if !inside(&outline, at) {
        return false;
    }
    let centre = view.flat(&die.centre);
    let aim = app.die_screen.throw.get_or_insert_with(|| Throw {
        passing,
        ..Throw::default()
    });
    aim.grab = (at.0 - centre.0, at.1 - centre.1);
    aim.drag = (0.0, 0.0);
    aim.pressed = Some((column, row));
    true
}

/// The mouse dragged to a cell: the throw's end is there (as far from the grab as the
/// mouse is from where it was pressed).
pub(crate) fn drag(app: &mut App, column: u16, row: u16) {
    let Some(cell) = view(app).map(|v| v.cell_size()) else {
        return;
    };
    if let Some(aim) = app.die_screen.throw.as_mut()
        && let Some((c0, r0)) = aim.pressed
    {
        aim.drag = (0.0, 0.0);
        aim.aim(cell, (column as f64 - c0 as f64, row as f64 - r0 as f64));
    }
}

/// The mouse released: a drag that went somewhere throws; one begun with Ctrl or Alt held
/// ends throw mode. Whether a drag of the throw's was under way.
pub(crate) fn release(app: &mut App) -> bool {
    let Some(aim) = app.die_screen.throw.as_mut() else {
        return false;
    };
    if aim.pressed.take().is_none() {
        return false;
    }
    let (moved, passing) = (aim.drag != (0.0, 0.0), aim.passing);
    if moved {
        throw(app);
    }
    if passing {
        app.die_screen.throw = None;
    }
    true
}

/// Throws: the start gets the aim's velocity and spin, and plays from t = 0.
fn throw(app: &mut App) {
    let Some(aim) = app.die_screen.throw else { return };
    let camera = app.die_screen.camera;
    let start = aim.start(&camera, &app.setup.params, &app.setup.initial);
    let c = app.setup.play(app.setup.params, start);
    app.send(c);
    let thrown = Thrown {
        velocity: start.velocity.into(),
        spin: start.angular_velocity.into(),
    };
    app.notice = Some(format!(
        "thrown: {} · {} saves the throw, {} throws it again",
        thrown.words(),
        label(Scope::Die, Action::SavePreset),
        label(Scope::Die, Action::Replay)
    ));
}
