//! What a program that shows a linkage takes when its user names nothing more than the
//! description: the input's speed, the output of the diagrams, the points whose paths the
//! plan traces, the crank pin whose reaction the hodograph follows, the end point of a
//! linkage with two inputs, and the table of a course with the named points' paths. The
//! `tmm` program and the `linkage` example both take these, so that the two agree.

use super::{Analysis, LinkId, Linkage, Output, Plan, Table};
use crate::Result;

/// The input speed of a description that gives none, rad/s (m/s for a slider).
pub const DEFAULT_SPEED: f64 = 10.0;

impl Linkage {
    /// The input speed of the course: the description's `speed`, or [`DEFAULT_SPEED`].
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{bundled, DEFAULT_SPEED};
    /// let mut linkage = bundled::four_bar();
    /// linkage.speed = None;
    /// assert_eq!(linkage.input_speed(), DEFAULT_SPEED);
    /// ```
    #[must_use]
    pub fn input_speed(&self) -> f64 {
        self.speed.unwrap_or(DEFAULT_SPEED)
    }
}

impl Plan {
    /// The joints whose paths a plan of the linkage shows: every joint off the frame (in the
    /// description's order), then every named point.
    ///
    /// # Examples
    /// The four-bar's frame hinges trace nothing; its coupler joints and its named coupler
    /// point do:
    /// ```
    /// use tmm::linkage::{bundled, LinkId, Plan};
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let traced = plan.traced_points();
    /// let points = plan.point_names();
    /// let (joints, named) = traced.split_at(traced.len() - points.len());
    /// assert_eq!(named, points.iter().map(String::as_str).collect::<Vec<_>>());
    /// assert_eq!(joints.len(), 2);
    /// for name in joints {
    ///     assert!(!plan.joint_links(*name)?.contains(&LinkId::FRAME));
    /// }
    /// # Ok::<(), tmm::Error>(())
    /// ```
    #[must_use]
    pub fn traced_points(&self) -> Vec<&str> {
        self.joint_names()
            .iter()
            .enumerate()
            .filter(|&(j, _)| {
                self.joint_links(j)
                    .is_ok_and(|l| !l.contains(&LinkId::FRAME))
            })
            .map(|(_, n)| n.as_str())
            .chain(self.point_names().iter().map(String::as_str))
            .collect()
    }

    /// The crank pin: the first input link's first joint off the frame, whose reaction a
    /// hodograph follows; `None` for an input link hinged to the frame alone.
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{bundled, Plan};
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let pin = plan.crank_pin().expect("the crank carries the coupler");
    /// let links = plan.joint_links(pin)?;
    /// assert!(links.contains(&plan.input_links()[0]));
    /// assert!(!links.contains(&tmm::linkage::LinkId::FRAME));
    /// # Ok::<(), tmm::Error>(())
    /// ```
    #[must_use]
    pub fn crank_pin(&self) -> Option<&str> {
        let input = self.input_links()[0];
        (0..self.joint_names().len())
            .find(|&j| {
                self.joint_links(j)
                    .is_ok_and(|l| l.contains(&input) && !l.contains(&LinkId::FRAME))
            })
            .map(|j| self.joint_names()[j].as_str())
    }

    /// The output of the diagrams: `described` (the description's `output`), or the angle of
    /// the last link written that is neither the frame nor an input link (the last link
    /// written when every link is one of those).
    #[must_use]
    pub fn output_or_last(&self, described: Option<&Output>) -> Output {
        described.cloned().unwrap_or_else(|| {
            let names = self.link_names();
            let inputs = self.input_links();
            let last = (1..names.len())
                .rev()
                .find(|&k| !inputs.contains(&LinkId(k)))
                .unwrap_or(names.len() - 1);
            Output::Angle(names[last].clone())
        })
    }

    /// The end point of a linkage with two inputs: the first joint on neither the frame nor an
    /// input link (the tip of a five-bar), if any.
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{bundled, Plan};
    /// let plan = Plan::new(&bundled::five_bar_robot())?;
    /// let tip = plan.end_joint().expect("the five-bar has a tip");
    /// let links = plan.joint_links(tip)?;
    /// assert!(links.iter().all(|l| !plan.input_links().contains(l)));
    /// # Ok::<(), tmm::Error>(())
    /// ```
    #[must_use]
    pub fn end_joint(&self) -> Option<&str> {
        let inputs = self.input_links();
        let free = |l: &LinkId| *l != LinkId::FRAME && !inputs.contains(l);
        (0..self.joint_names().len())
            .find(|&j| self.joint_links(j).is_ok_and(|l| l.iter().all(free)))
            .map(|j| self.joint_names()[j].as_str())
    }

    /// Every position of `inputs` analysed on its own (a failure stays in its place), with
    /// `progress` told the index of each position before it is solved.
    pub fn analyse_each<I>(
        &self,
        inputs: &[I],
        progress: &mut dyn FnMut(usize),
    ) -> Vec<Result<Analysis<'_>>>
    where
        I: Clone + Into<super::Inputs>,
    {
        inputs
            .iter()
            .enumerate()
            .map(|(k, i)| {
                progress(k);
                self.analyse(i.clone())
            })
            .collect()
    }

    /// The course table of `analyses` ([`Table::of`]: the failed positions left out, and any
    /// row with a value that is not finite) with the named points' paths: x, y, |v|, |a| of
    /// each named point (of the analyses' plan), placed after the joints' columns and before
    /// the transmission angles and the reactions.
    ///
    /// # Examples
    /// Jansen's leg has a named foot; its path is in the table, on the linkage:
    /// ```
    /// use tmm::linkage::{bundled, uniform_inputs, Plan};
    /// let plan = Plan::new(&bundled::jansen_leg())?;
    /// let foot = plan.point_names()[0].clone();
    /// let inputs = uniform_inputs(12, plan.reference_input(), 10.0, 0.0);
    /// let analyses = plan.analyse_each(&inputs, &mut |_| {});
    /// let table = plan.course_table(&analyses);
    /// let x = table.column(&format!("x({foot}) [m]")).expect("the foot's path");
    /// let p = analyses[3].as_ref().unwrap().kinematics().point(foot.as_str())?.p;
    /// assert_eq!(x[3], p.x);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    #[must_use]
    pub fn course_table(&self, analyses: &[Result<Analysis<'_>>]) -> Table {
        // One row per analysis, the points written with the rest, so that a row left out
        // (a value that is not finite, see `Table::push`) leaves out its points too.
        super::table::course_table(analyses)
    }
}
