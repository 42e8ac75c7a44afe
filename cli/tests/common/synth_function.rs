//! The argument list of `tmm synth function` the tests share (the program's tests, the
//! newcomer's and the hostile sweep ran it with the same twelve arguments each).

/// `tmm synth function` for y = `function`(x) over `x` ("x0,x1"), the crank over `crank`
/// and the rocker over `rocker` ("from,to" in degrees), the frame `frame` (m). The default
/// is the help's example: y = log10(x), x from 1 to 2, the crank from −30° to 30°, the
/// rocker from 0° to 90°, the frame 0.1 m; a test changes the fields it is about.
#[derive(Debug, Clone, Copy)]
pub struct SynthFunction<'a> {
    pub function: &'a str,
    pub x: &'a str,
    pub crank: &'a str,
    pub rocker: &'a str,
    pub frame: &'a str,
}

impl Default for SynthFunction<'_> {
    fn default() -> Self {
        Self {
            function: "log10",
            x: "1,2",
            crank: "-30,30",
            rocker: "0,90",
            frame: "0.1",
        }
    }
}

impl<'a> SynthFunction<'a> {
    /// The arguments after `synth` (`function`, then its options), then `extra`.
    pub fn args(&self, extra: &[&'a str]) -> Vec<&'a str> {
        let mut a = vec![
            "function",
            "--function",
            self.function,
            "--x",
            self.x,
            "--crank",
            self.crank,
            "--rocker",
            self.rocker,
            "--frame",
            self.frame,
        ];
        a.extend_from_slice(extra);
        a
    }

    /// The whole command line: `synth`, [`SynthFunction::args`].
    pub fn command(&self, extra: &[&'a str]) -> Vec<&'a str> {
        let mut a = vec!["synth"];
        a.extend(self.args(extra));
        a
    }
}
