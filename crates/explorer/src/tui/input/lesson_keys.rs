//! The lesson's keys: the next step and the step before. A step closes whatever is open,
//! opens its preset with the step's view over the preset's own (the worker sets the speed
//! and rolls a twin, the view's arrows and screen come back with its snapshot), sets the
//! plot (the energy terms unless the step names another), and puts the step's card up; the first key that is not a lesson key puts it down
//! and does what it does on the screen.

use crate::tui::input::map_keys as map;
use crate::tui::state::app::{App, Page};
use crate::tui::state::die_screen::PlotChoice;
use crate::tui::vocabulary::key_table::{Action, Scope, label};

/// `PageDown`: the card down, or the next step; `PageUp`: the step before.
pub(crate) fn on_step_key(app: &mut App, action: Action) {
    let Some(run) = app.lesson.as_mut() else {
        app.notice = Some("no lesson: `dicesim tui --lesson` walks the shipped one".to_string());
        return;
    };
    let next = match (action, run.at) {
        (Action::NextStep, Some(_)) if run.card => {
            run.card = false;
            return;
        }
        (Action::NextStep, None) => 0,
        (Action::NextStep, Some(i)) if i + 1 < run.len() => i + 1,
        (Action::NextStep, Some(_)) => {
            run.card = false;
            app.notice = Some(format!(
                "the lesson's last step ({} goes back a step)",
                label(Scope::Die, Action::PreviousStep)
            ));
            return;
        }
        (_, Some(i)) if i > 0 => i - 1,
        _ => {
            app.notice = Some(format!(
                "the lesson's first step ({} goes on)",
                label(Scope::Die, Action::NextStep)
            ));
            return;
        }
    };
    open_step(app, next);
}

/// Opens step `i` of the lesson and puts its card up.
pub(crate) fn open_step(app: &mut App, i: usize) {
    let Some(step) = app.lesson.as_ref().and_then(|r| r.lesson.steps.get(i)).cloned() else {
        return;
    };
    app.overlay = None;
    app.die_screen.throw = None;
    if app.page == Page::Map {
        map::close(app);
    }
    if step.twin_off && app.twin.on {
        let c = app.twin.toggle();
        app.send(c);
    }
    app.load(step.preset);
    app.page = if step.presentation {
        Page::Presentation
    } else {
        Page::Die
    };
    // The step's plot, the energy terms unless it names another: not the plot the step
    // before left, so a step reached by PageUp looks as it did by PageDown.
    app.die_screen.plot = PlotChoice {
        quantity: step.plot,
        ..PlotChoice::default()
    };
    if let Some(row) = step.select {
        app.die_screen.selected = row;
    }
    if let Some(fit) = step.fit {
        app.die_screen.plot.fitted = fit;
    }
    if let Some(run) = app.lesson.as_mut() {
        run.at = Some(i);
        run.card = true;
    }
}

/// Any key but the lesson's puts the card down (and then does what it does).
pub(crate) fn card_down(app: &mut App, action: Option<Action>) {
    if matches!(action, Some(Action::NextStep | Action::PreviousStep)) {
        return;
    }
    if let Some(run) = app.lesson.as_mut() {
        run.card = false;
    }
}
