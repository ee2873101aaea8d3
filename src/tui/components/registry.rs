//! The panel registry's machinery: the `registry!` macro, which turns the one list of
//! panels in [`super`] (each panel's target, field, type, slot and constructor) into
//! * [`super::Target`]: one per panel, the address of its background work and restarts;
//! * [`super::Msg`]: the typed message enum, one variant per panel carrying that
//!   panel's own [`super::Component::Msg`] (no `Any`, no downcast);
//! * [`super::Registered`] for each panel type (its target and its [`super::Address`]);
//! * [`super::Panels`]: one of each panel, and every routing over them, all in the
//!   list's order: actions (the first panel that consumes one ends the search),
//!   parameter changes, focus moves, starts and messages by target, what is computing,
//!   the layout's panes, which panel a slot shows (the first one listed there that is
//!   shown: a panel listed before another in the same slot takes its place while shown),
//!   the focus ring (the slots whose shown panel takes the focus), and drawing.
//!
//! The macro holds no list of its own: a panel is added by its line in the registry.

/// See the module's header.
macro_rules! registry {
    ($(
        $(#[$doc:meta])*
        $target:ident => $field:ident: $ty:ty, slot $slot:expr, new $make:expr;
    )*) => {
        /// A panel, as the address of its background work and of its restarts (one per
        /// panel in the registry).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Target {
            $($target),*
        }

        impl Target {
            /// Every panel, in routing order.
            pub const ALL: &'static [Target] = &[$(Target::$target),*];
        }

        /// A message from a panel's background work: the generation it ran under and
        /// what it carries, typed per panel ([`Component::Msg`]).
        pub enum Msg {
            $($target(u64, <$ty as $crate::tui::components::Component>::Msg)),*
        }

        impl Msg {
            /// The panel the message is for.
            pub fn target(&self) -> Target {
                match self {
                    $(Msg::$target(..) => Target::$target),*
                }
            }

            /// The generation of the work that sent it.
            pub fn gen(&self) -> u64 {
                match self {
                    $(Msg::$target(gen, _) => *gen),*
                }
            }
        }

        impl std::fmt::Debug for Msg {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                write!(f, "Msg {{ to: {:?}, gen: {} }}", self.target(), self.gen())
            }
        }

        impl $crate::tui::workers::Mail for Msg {
            type Target = Target;
            const TARGETS: &'static [Target] = Target::ALL;
        }

        $(
            impl $crate::tui::components::Registered for $ty {
                const TARGET: Target = Target::$target;
                const ADDRESS: $crate::tui::components::Address<
                    <$ty as $crate::tui::components::Component>::Msg,
                > = $crate::tui::workers::Address {
                    to: Target::$target,
                    wrap: Msg::$target,
                };
            }
        )*

        /// One of each panel, in routing order.
        pub struct Panels {
            $($(#[$doc])* pub $field: $ty),*
        }

        impl Panels {
            /// Every panel, fresh, for the shared state.
            pub fn new(shared: &Shared) -> Panels {
                Panels {
                    $($field: ($make)(shared)),*
                }
            }

            /// Hand `action` to the panels in order until one consumes it; true if one
            /// did.
            pub fn handle(&mut self, action: Action, shared: &mut Shared) -> bool {
                $(
                    if self.$field.handle(action, shared) {
                        return true;
                    }
                )*
                false
            }

            /// Tell every panel that row `id` changed.
            pub fn changed(&mut self, id: ParamId, shared: &mut Shared) {
                $(self.$field.changed(id, shared);)*
            }

            /// Tell every panel that the focus moved.
            pub fn focus_moved(&mut self) {
                $(self.$field.focus_moved();)*
            }

            /// Start panel `t`'s background work.
            pub fn start(&mut self, t: Target, shared: &mut Shared, workers: &Workers) {
                match t {
                    $(Target::$target => self.$field.start(shared, workers)),*
                }
            }

            /// Hand a message to the panel it is for.
            pub fn receive(&mut self, msg: Msg, shared: &mut Shared) {
                match msg {
                    $(Msg::$target(gen, m) => self.$field.receive(gen, m, shared)),*
                }
            }

            /// Whether any panel's background work may still send something.
            pub fn busy(&self) -> bool {
                false $(|| self.$field.busy())*
            }

            /// What the panels are computing, for the status line.
            pub fn computing(&self, shared: &Shared) -> Vec<String> {
                let mut out = Vec::new();
                $(out.extend(self.$field.computing(shared));)*
                out
            }

            /// The panel shown in `slot`: the first one listed there that is shown.
            pub fn in_slot(&self, slot: Slot) -> Option<Target> {
                $(
                    if $slot == Some(slot) && self.$field.shown() {
                        return Some(Target::$target);
                    }
                )*
                None
            }

            /// The slots that take the focus, in order: those whose shown panel is
            /// focusable.
            pub fn focus_ring(&self) -> Vec<Slot> {
                let mut ring = Vec::new();
                $(
                    if let Some(s) = $slot {
                        if self.in_slot(s) == Some(Target::$target)
                            && self.$field.focusable()
                            && !ring.contains(&s)
                        {
                            ring.push(s);
                        }
                    }
                )*
                ring
            }

            /// Give every panel with a slot its rectangle (shown or not, so a panel
            /// shown later has its size).
            pub fn set_panes(&mut self, panes: &Panes, shared: &mut Shared) {
                $(
                    if let Some(s) = $slot {
                        self.$field.set_pane(panes.get(s), shared);
                    }
                )*
            }

            /// Draw the panel shown in each slot (a slot the layout left out at this
            /// size has no area and is skipped).
            pub fn draw(&self, shared: &Shared, panes: &Panes, buf: &mut Buffer) {
                $(
                    if let Some(s) = $slot {
                        let area = panes.get(s);
                        if self.in_slot(s) == Some(Target::$target) && !area.is_empty() {
                            self.$field.draw(shared, area, buf);
                        }
                    }
                )*
            }
        }
    };
}
