//! The keys of the terminal application, from the key table the application uses (the
//! same table the `?` overlay is drawn from).

use crate::tui::keymap::{Action, Keymap, KEY_NAMES};

pub fn markdown() -> String {
    let keys = Keymap::default();
    let mut out = String::from(
        "# Keys of the terminal application\n\n\
         The default bindings, as the `?` overlay lists them. This page is generated from\n\
         the application's key table (`bouncemap generate-docs`); a test keeps it equal to\n\
         the binary. The `config name` is the action's name in the `[keys]` section of the\n\
         config file (see [commands.md](commands.md#config-file)).\n\n\
         | keys | config name | action |\n| --- | --- | --- |\n",
    );
    for (action, (bound, what)) in Action::ALL.iter().zip(keys.help()) {
        let bound = bound.replace('|', "\\|").replace('`', "");
        out.push_str(&format!(
            "| `{bound}` | `{}` | {} |\n",
            action.name(),
            what.replace('|', "\\|")
        ));
    }
    out.push_str(&format!(
        "\nIn a `[keys]` entry a key is a character (`\"N\"`, `\"+\"`), or `ctrl-`, `alt-` or\n\
         `shift-` followed by one of: {KEY_NAMES}. Ctrl-C always quits, whatever the file\n\
         binds; a key bound to two actions, or quit left without a key, is refused.\n"
    ));
    out
}
