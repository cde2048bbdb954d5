//! How a step integrates the bristles' moves: the one scheme type and the table the configuration, the CLI and the FMU name it by.

/// How [`Contact::step`](crate::Contact::step) (and the steady march) advances the bristles.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Scheme {
    /// One sub-step per cell crossing for every bristle (the steady march's cells), new
    /// bristles by a march. Independent of the communication step within 0.5 %.
    CellsMarch,
    /// Faster (about 3x fewer bristle moves at 0.1-0.25 ms steps on 80x21): the bristles
    /// that stay move continuously, in equal sub-steps of at most
    /// [`MAX_SUBSTEP_CELLS`](crate::engine::MAX_SUBSTEP_CELLS) cells, cut into one-cell pieces
    /// within [`EDGE_CELLS`](crate::engine::EDGE_CELLS) cells of the trailing edge and ending
    /// each step with a one-cell piece; a sub-step of n > 1 cells weighs its start stress by
    /// (1 - 1/n)/2 in its dissipation (Eq. 4.29), as n one-cell moves would. Bristles that
    /// enter during the step are marched cell by cell. On 80x21 its dependence on the
    /// communication step after a creepage step at 20 m/s (1 x 1 ms vs 10 x 0.1 ms) is
    /// 0.05-0.4 % for table4.1 (within the grid's own error) and 0.9-1.5 % for dry; forces
    /// under inputs that jump every step follow [`Scheme::CellsMarch`] within 1.5 %
    /// (docs/model.md section 3).
    Continuous,
    /// [`Scheme::CellsMarch`] with the higher-order rules along each move (ECF's
    /// same-characteristic law; docs/model.md section 3.3): tau_c2 linear and 1/L_p along the
    /// move's temperature profile from the start material's to the end material's, the
    /// newest interval of Eq. 4.35 with the heat rate linear over the move, the move from
    /// the leading edge in graded sub-moves, and the leading cell's sqrt(s) term in the
    /// quadrature. About twice the cost of [`Scheme::CellsMarch`] on the same grid, and more
    /// accurate on a grid of equal cost. FASTSIM (and any other perfectly plastic or
    /// elastic-unloading layer) takes [`Scheme::CellsMarch`].
    CellsHigher,
}

/// One scheme's names: in a configuration file, on the command line and in the accuracy
/// table (`name`), and as the FMU's parameter `scheme` (`fmu_code`).
#[derive(Clone, Copy, Debug)]
pub struct SchemeRow {
    /// The scheme.
    pub scheme: Scheme,
    /// Its name (configuration key `scheme`, `ecf --scheme`, the accuracy table's column).
    pub name: &'static str,
    /// Its code in the FMU's integer parameter `scheme` and in FMU states (0 there: not set).
    pub fmu_code: i32,
    /// True if it changes a steady state too (a steady computation offers it); the
    /// continuous scheme's steady state is the cells' march.
    pub steady: bool,
    /// One line for the command line's help.
    pub help: &'static str,
}

/// Every scheme with its names, in the order the messages list them.
pub const SCHEMES: [SchemeRow; 3] = [
    SchemeRow {
        scheme: Scheme::CellsMarch,
        name: "cells",
        fmu_code: 3,
        steady: true,
        help: "Cell by cell: the first-order reference, independent of the time step within 0.5 %",
    },
    SchemeRow {
        scheme: Scheme::Continuous,
        name: "continuous",
        fmu_code: 1,
        steady: false,
        help: "Continuous sub-steps of up to 8 cells: 2-4x faster on 80x21 at 0.1-1 ms steps, \
               its dependence on the time step up to about 1 %",
    },
    SchemeRow {
        scheme: Scheme::CellsHigher,
        name: "cells-ho",
        fmu_code: 2,
        steady: true,
        help: "Cell by cell with higher-order rules along each move (docs/model.md section 3.3): \
               about twice the cost of cells on the same grid, more accurate at equal cost; \
               ECF's default",
    },
];

impl Scheme {
    /// The names a configuration file and the command line give the schemes.
    pub const NAMES: &'static str = "cells, continuous or cells-ho";

    /// The scheme's row of [`SCHEMES`].
    pub fn row(self) -> &'static SchemeRow {
        match self {
            Scheme::CellsMarch => &SCHEMES[0],
            Scheme::Continuous => &SCHEMES[1],
            Scheme::CellsHigher => &SCHEMES[2],
        }
    }

    /// The scheme's name in a configuration file, the accuracy table and on the command line.
    pub fn name(self) -> &'static str {
        self.row().name
    }

    /// The scheme of a name ([`Scheme::name`]), None for any other text.
    pub fn by_name(name: &str) -> Option<Scheme> {
        SCHEMES.iter().find(|r| r.name == name).map(|r| r.scheme)
    }

    /// The scheme's code in the FMU's parameter `scheme` (1 to 3).
    pub fn fmu_code(self) -> i32 {
        self.row().fmu_code
    }

    /// The scheme of an FMU code ([`Scheme::fmu_code`]), None for any other code.
    pub fn by_fmu_code(code: i32) -> Option<Scheme> {
        SCHEMES
            .iter()
            .find(|r| r.fmu_code == code)
            .map(|r| r.scheme)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every row is its scheme's, names and codes are distinct and round-trip, and
    /// [`Scheme::NAMES`] lists the table's names in its order.
    #[test]
    fn the_table_names_each_scheme_once() {
        for (i, r) in SCHEMES.iter().enumerate() {
            assert_eq!(r.scheme.row().name, r.name);
            assert_eq!(Scheme::by_name(r.name), Some(r.scheme));
            assert_eq!(Scheme::by_fmu_code(r.fmu_code), Some(r.scheme));
            for q in &SCHEMES[i + 1..] {
                assert!(q.scheme != r.scheme && q.name != r.name && q.fmu_code != r.fmu_code);
            }
        }
        let names: Vec<_> = SCHEMES.iter().map(|r| r.name).collect();
        let (last, rest) = names.split_last().expect("rows");
        assert_eq!(Scheme::NAMES, format!("{} or {last}", rest.join(", ")));
        assert_eq!(Scheme::by_name("ho"), None);
        assert_eq!(Scheme::by_fmu_code(0), None);
    }
}
