//! Ask/tell over the design search: the same NSGA-II as [`search::search`] (the `moors` crate,
//! the same operators, population, generations, phases and seed: both run the search's one
//! optimiser driver), but the designs are evaluated by the caller, anywhere (a Dask cluster,
//! another machine), and told back.
//!
//! `moors` has no ask/tell interface of its own: its genetic algorithm calls a fitness
//! function with each batch and waits for the answer. So the algorithm runs on a thread of
//! its own whose fitness function hands each batch of new points out ([`AskTell::ask`]) and
//! waits until every one has been told ([`AskTell::tell`]). Everything else is the search's:
//! each point evaluated once (a point seen before costs nothing), the budget, the penalty of
//! a point without a value, the front of every feasible design evaluated, the hypervolume's
//! reference fixed from the first batch. A point whose design fails its check is never asked:
//! it is settled here as the search settles it (an error). So when every told result is the
//! one [`Problem::evaluate`] gives for the point, the candidates, their order and the front
//! are exactly those of [`search::search`] with the same seed.

use std::collections::{HashMap, VecDeque};
use std::sync::mpsc::{self, Receiver, Sender};
use std::thread::JoinHandle;

use super::search::{self, Bound, Candidate, Column, Outcome, Problem, Sense, Settings, Value};
use crate::error::ThudError;

pub use super::search::Failure;

/// A point's identity: its values, bit for bit.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
enum Key {
    Number(u64),
    Choice(String),
}

fn key(values: &[Value]) -> Vec<Key> {
    values
        .iter()
        .map(|v| match v {
            Value::Number(x) => Key::Number(x.to_bits()),
            Value::Choice(s) => Key::Choice(s.clone()),
        })
        .collect()
}

/// A batch the algorithm waits for: the first index of its new points and the points.
type Batch = (usize, Vec<Vec<Value>>);

/// A design search whose designs the caller evaluates: [`AskTell::ask`] for points,
/// [`AskTell::tell`] with what each gave, until [`AskTell::done`].
pub struct AskTell {
    problem: Problem,
    settings: Settings,
    /// The columns a told result carries, in this order ([`AskTell::columns`]).
    columns: Vec<Column>,
    batches: Receiver<Batch>,
    answers: Sender<Vec<Candidate>>,
    /// The batch under way: its first index and one slot per point (filled when told).
    current: Option<(usize, Vec<Option<Candidate>>)>,
    /// The points of the batch under way.
    points: Vec<Vec<Value>>,
    /// Points of the batch under way not asked yet (their index in the batch).
    waiting: VecDeque<usize>,
    /// Points asked and not told yet, by key: their index in the batch.
    asked: HashMap<Vec<Key>, usize>,
    all: Vec<Candidate>,
    reference: Option<Vec<f64>>,
    given_reference: bool,
    finished: bool,
    thread: Option<JoinHandle<Result<(), Failure>>>,
    failure: Option<String>,
}

impl std::fmt::Debug for AskTell {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("AskTell")
            .field("evaluations", &self.all.len())
            .field("done", &self.finished)
            .finish_non_exhaustive()
    }
}

impl AskTell {
    /// A search of `problem` with `settings` (budget and seed), the hypervolume against
    /// `reference` when given (two objectives; else fixed from the first batch, as the search).
    pub fn new(problem: Problem, settings: Settings, reference: Option<Vec<f64>>) -> Result<AskTell, ThudError> {
        problem.check()?;
        let mut columns: Vec<Column> = problem.objectives.iter().map(|o| o.column).collect();
        for c in &problem.constraints {
            if let Bound::Result(col) = c.bound {
                if !columns.contains(&col) {
                    columns.push(col);
                }
            }
        }
        let (batch_tx, batch_rx) = mpsc::channel::<Batch>();
        let (answer_tx, answer_rx) = mpsc::channel::<Vec<Candidate>>();
        let p = problem.clone();
        let thread = std::thread::Builder::new()
            .name("thud-design-asktell".into())
            .spawn(move || run(&p, settings, &batch_tx, &answer_rx))
            .map_err(|e| ThudError::invalid("design", format!("cannot start the search: {e}")))?;
        Ok(AskTell {
            problem,
            settings,
            columns,
            batches: batch_rx,
            answers: answer_tx,
            current: None,
            points: Vec::new(),
            waiting: VecDeque::new(),
            asked: HashMap::new(),
            all: Vec::new(),
            given_reference: reference.is_some(),
            reference,
            finished: false,
            thread: Some(thread),
            failure: None,
        })
    }

    /// The problem searched.
    #[must_use]
    pub fn problem(&self) -> &Problem {
        &self.problem
    }

    /// The budget and seed.
    #[must_use]
    pub fn settings(&self) -> Settings {
        self.settings
    }

    /// The result columns a told result carries, in order: the objectives' columns, then
    /// those of the constraints on results (each once).
    #[must_use]
    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    /// Whether the search is over: its budget spent or its generations run, every point told.
    #[must_use]
    pub fn done(&self) -> bool {
        self.finished
    }

    /// Points asked and not told yet.
    #[must_use]
    pub fn outstanding(&self) -> usize {
        self.asked.len()
    }

    /// Up to `n` points to evaluate, each one value per variable. Fewer (or none) while the
    /// batch under way waits for points already asked to be told; none once [`Self::done`].
    pub fn ask(&mut self, n: usize) -> Result<Vec<Vec<Value>>, ThudError> {
        // A batch whose points all fail their check is settled at once: on to the next.
        while self.current.is_none() && !self.finished {
            self.next_batch()?;
        }
        let mut out = Vec::new();
        while out.len() < n {
            let Some(i) = self.waiting.pop_front() else { break };
            let values = self.points[i].clone();
            self.asked.insert(key(&values), i);
            out.push(values);
        }
        Ok(out)
    }

    /// Tells what the point `values` (as asked) gave: `Ok` with one value per column of
    /// [`Self::columns`] (None where the run has none, e.g. no impact), or `Err` with why it
    /// could not be run. Refuses a point not asked or told already. With a band, see
    /// [`Self::tell_runs`].
    pub fn tell(&mut self, values: &[Value], result: Result<Vec<Option<f64>>, Failure>) -> Result<(), ThudError> {
        self.tell_runs(values, result.map(|v| vec![v]))
    }

    /// Tells what the point `values` (as asked) gave, one run at a time: `Ok` with one row per
    /// run of the point ([`Problem::runs_at`]: the design itself, or one per frequency of the
    /// band, in the band's order), each one value per column of [`Self::columns`]; each
    /// objective and result constraint is then taken at its worst over the runs, as the
    /// search takes it. `Err` with why the point could not be run. Refuses a point not asked
    /// or told already, and a count of runs or values that is not the problem's.
    pub fn tell_runs(
        &mut self,
        values: &[Value],
        result: Result<Vec<Vec<Option<f64>>>, Failure>,
    ) -> Result<(), ThudError> {
        let k = key(values);
        let Some(i) = self.asked.remove(&k) else {
            return Err(ThudError::invalid("tell", format!("{} was not asked, or is told already", shown(values))));
        };
        if let Ok(runs) = &result {
            let want = self.problem.band_hz.len().max(1);
            let why = if runs.len() == want {
                runs.iter()
                    .find(|v| v.len() != self.columns.len())
                    .map(|v| format!("{} values told for {} columns", v.len(), self.columns.len()))
            } else {
                Some(format!("{} runs told for a point of {want} (one per frequency of the band)", runs.len()))
            };
            if let Some(why) = why {
                self.asked.insert(k, i);
                return Err(ThudError::invalid("tell", why));
            }
        }
        let Some((first, slots)) = &mut self.current else {
            return Err(ThudError::invalid("tell", "no batch under way"));
        };
        let index = *first + i;
        let candidate = match result {
            Ok(runs) => candidate(&self.problem, &self.columns, index, values.to_vec(), &runs),
            Err(why) => failed(&self.problem, index, values.to_vec(), why.0),
        };
        slots[i] = Some(candidate);
        self.finish_batch_if_told();
        Ok(())
    }

    /// What the search has found so far (marked partial until [`Self::done`]).
    #[must_use]
    pub fn outcome(&self) -> Outcome {
        let front = self.problem.front(&self.all);
        let hypervolume = self.reference.as_ref().and_then(|r| self.problem.hypervolume(&self.all, &front, r));
        Outcome {
            all: self.all.clone(),
            front,
            partial: !self.finished,
            reference: self.reference.clone(),
            hypervolume,
        }
    }

    /// Waits for the algorithm's next batch; settles at once the points whose design fails
    /// its check (never asked); marks the search done when the algorithm has ended.
    fn next_batch(&mut self) -> Result<(), ThudError> {
        let Ok((first, points)) = self.batches.recv() else {
            // The algorithm has ended (its generations run, or it failed).
            self.finished = true;
            if let Some(t) = self.thread.take() {
                match t.join() {
                    Ok(Ok(())) => {}
                    Ok(Err(e)) => self.failure = Some(e.0),
                    Err(_) => self.failure = Some("the optimiser stopped unexpectedly".into()),
                }
            }
            return match &self.failure {
                Some(e) => Err(ThudError::invalid("evaluations", e.clone())),
                None => Ok(()),
            };
        };
        let mut slots: Vec<Option<Candidate>> = vec![None; points.len()];
        self.waiting.clear();
        for (i, p) in points.iter().enumerate() {
            match self.problem.runs_at(p) {
                Ok(_) => self.waiting.push_back(i),
                Err(e) => slots[i] = Some(failed(&self.problem, first + i, p.clone(), e.to_string())),
            }
        }
        self.points = points;
        self.current = Some((first, slots));
        self.finish_batch_if_told();
        Ok(())
    }

    /// Hands a fully told batch back to the algorithm and keeps its candidates.
    fn finish_batch_if_told(&mut self) {
        let complete = self.current.as_ref().is_some_and(|(_, s)| s.iter().all(Option::is_some));
        if !complete {
            return;
        }
        let Some((_, slots)) = self.current.take() else { return };
        let done: Vec<Candidate> = slots.into_iter().flatten().collect();
        self.all.extend(done.iter().cloned());
        if !self.given_reference && self.reference.is_none() && self.problem.objectives.len() == 2 {
            self.reference = worst(&self.problem, &self.all);
        }
        // The algorithm gone (it failed): the next ask finds out.
        let _ = self.answers.send(done);
    }
}

/// The worst value of each objective among the feasible designs (the search's reference).
fn worst(problem: &Problem, all: &[Candidate]) -> Option<Vec<f64>> {
    problem
        .objectives
        .iter()
        .enumerate()
        .map(|(k, o)| {
            all.iter().filter(|c| c.feasible()).filter_map(|c| c.objectives[k]).reduce(|a, b| match o.sense {
                Sense::Minimize => a.max(b),
                Sense::Maximize => a.min(b),
            })
        })
        .collect()
}

/// A point as a message shows it.
fn shown(values: &[Value]) -> String {
    let parts: Vec<String> = values
        .iter()
        .map(|v| match v {
            Value::Number(x) => x.to_string(),
            Value::Choice(s) => s.clone(),
        })
        .collect();
    format!("({})", parts.join(", "))
}

/// The candidate of a point that could not be run.
fn failed(problem: &Problem, index: usize, values: Vec<Value>, why: String) -> Candidate {
    Candidate {
        index,
        values,
        objectives: vec![None; problem.objectives.len()],
        margins: vec![None; problem.constraints.len()],
        error: Some(why),
    }
}

/// The candidate of a point whose runs gave `told` (one row per run, one value per column of
/// `columns`): objectives and result constraints read from it at their worst over the runs
/// (none where a run has no value), as [`Problem::evaluate`] takes them; parameter
/// constraints from the design.
fn candidate(
    problem: &Problem,
    columns: &[Column],
    index: usize,
    values: Vec<Value>,
    told: &[Vec<Option<f64>>],
) -> Candidate {
    // A column at its worst over the runs: the greatest where `high` is worse, else the least.
    let worst = |col: Column, high: bool| -> Option<f64> {
        let i = columns.iter().position(|c| *c == col)?;
        let mut acc: Option<f64> = None;
        for run in told {
            let v = run[i]?;
            acc = Some(acc.map_or(v, |a: f64| if high { a.max(v) } else { a.min(v) }));
        }
        acc
    };
    let design = match problem.design_at(&values) {
        Ok(d) => d,
        Err(e) => return failed(problem, index, values, e.to_string()),
    };
    let objectives = problem.objectives.iter().map(|o| worst(o.column, o.sense == Sense::Minimize)).collect();
    let margins = problem
        .constraints
        .iter()
        .map(|c| {
            let actual = match c.bound {
                Bound::Result(col) => worst(col, c.at_most),
                Bound::Param(row) => row.get.map(|get| get(design.design())),
            };
            actual.map(|a| if c.at_most { c.value - a } else { a - c.value })
        })
        .collect();
    Candidate { index, values, objectives, margins, error: None }
}

/// The algorithm's side: NSGA-II as [`search::search`] runs it, each batch's new points sent
/// out and their candidates awaited.
fn run(
    problem: &Problem,
    settings: Settings,
    batches: &Sender<Batch>,
    answers: &Receiver<Vec<Candidate>>,
) -> Result<(), Failure> {
    let n = settings.evaluations;
    let archive = std::sync::Mutex::new(Mirror { seen: HashMap::new(), all: Vec::new(), gone: false });
    let look = |genes: &[Vec<f64>], cap: usize| -> Vec<Option<Candidate>> {
        let mut st = archive.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let points: Vec<Vec<Value>> = genes.iter().map(|g| problem.decode(g)).collect();
        let keys: Vec<Vec<Key>> = points.iter().map(|p| key(p)).collect();
        let mut new: Vec<(Vec<Key>, Vec<Value>)> = Vec::new();
        for (k, p) in keys.iter().zip(&points) {
            if !st.seen.contains_key(k) && !new.iter().any(|(m, _)| m == k) {
                new.push((k.clone(), p.clone()));
            }
        }
        let room = if st.gone { 0 } else { cap.min(n).saturating_sub(st.all.len()) };
        new.truncate(room);
        if !new.is_empty() {
            let first = st.all.len();
            let sent = batches.send((first, new.iter().map(|(_, p)| p.clone()).collect()));
            match sent.ok().and_then(|()| answers.recv().ok()) {
                Some(done) => {
                    for ((k, _), c) in new.into_iter().zip(done) {
                        st.seen.insert(k, c.index);
                        st.all.push(c);
                    }
                }
                // The caller is gone: no more evaluations; the generations left run out.
                None => st.gone = true,
            }
        }
        keys.iter().map(|k| st.seen.get(k).map(|&i| st.all[i].clone())).collect()
    };
    // The defaults (NSGA-II) read no reference point: none is handed over.
    search::run_moors(problem, search::Tuning::default(), n, settings.seed, &look, &|| None)
}

/// The algorithm's copy of the archive: each point's index, every candidate in order.
struct Mirror {
    seen: HashMap<Vec<Key>, usize>,
    all: Vec<Candidate>,
    gone: bool,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::search::tests::paper_problem_with as problem;
    use crate::design::search::{Constraint, Objective};

    /// Drives an ask/tell search to its end, evaluating each run of each point as one run
    /// (`thud simulate`) does, `n` points asked at a time, told in reverse order.
    fn drive(p: &Problem, s: Settings, n: usize) -> Outcome {
        let mut at = AskTell::new(p.clone(), s, None).unwrap();
        let columns = at.columns().to_vec();
        while !at.done() {
            let xs = at.ask(n).unwrap();
            for x in xs.iter().rev() {
                let runs = p.runs_at(x).unwrap();
                let told: Result<Vec<Vec<Option<f64>>>, Failure> = runs
                    .iter()
                    .map(|r| {
                        let e = crate::design::evaluate(r, 0, None).map_err(|e| Failure(e.to_string()))?;
                        Ok(columns.iter().map(|col| col.value(&e.metrics, e.steady.as_ref())).collect())
                    })
                    .collect();
                if runs.len() == 1 {
                    at.tell(x, told.map(|mut t| t.remove(0))).unwrap();
                } else {
                    at.tell_runs(x, told).unwrap();
                }
            }
        }
        at.outcome()
    }

    #[test]
    fn told_each_frequency_s_run_of_a_band_it_finds_the_band_search_s_front() {
        // Worst steady amplitude against worst Leq over 4.5, 5 and 5.5 Hz (around the
        // structure's 5.03 Hz), the ball at most 80 g: the command line's forced-band problem.
        let mut d = crate::design::Design::default();
        d.damper.force_n = 2.0;
        d.damper.freq_hz = 5.0;
        d.damper.duration_s = 3.0;
        let p = Problem {
            base: d.check().unwrap(),
            variables: vec![
                search::Variable::parse_range("mass=20g:120g").unwrap(),
                search::Variable::parse_range("gap=1cm:6cm").unwrap(),
            ],
            objectives: vec![
                Objective::parse("steady_amplitude_m", Sense::Minimize).unwrap(),
                Objective::parse("steady_leq_db", Sense::Minimize).unwrap(),
            ],
            constraints: vec![Constraint::parse("mass<=80g").unwrap(), Constraint::parse("steady_leq_db>=0").unwrap()],
            band_hz: vec![4.5, 5.0, 5.5],
            robust: None,
        };
        let s = Settings { evaluations: 24, seed: 2 };
        let want = search::search(&p, s, None, None, &|_, _, _| {}).unwrap();
        assert!(!want.front.is_empty());
        let got = drive(&p, s, 5);
        assert_eq!(got.all, want.all);
        assert_eq!(got.front, want.front);
        assert_eq!(got.hypervolume, want.hypervolume);
        // One run told for a point of three is refused, and the point stays asked.
        let mut at = AskTell::new(p.clone(), s, None).unwrap();
        let x = at.ask(1).unwrap().remove(0);
        let e = at.tell(&x, Ok(vec![Some(0.01), Some(80.0)])).unwrap_err();
        assert!(e.to_string().contains("1 runs told for a point of 3"), "{e}");
        assert_eq!(at.outstanding(), 1);
    }

    #[test]
    fn told_the_search_s_own_evaluations_it_finds_the_search_s_front() {
        let p = problem(vec![Constraint::parse("mass<=80g").unwrap(), Constraint::parse("spl_max_db<=104").unwrap()]);
        let s = Settings { evaluations: 60, seed: 3 };
        let want = search::search(&p, s, None, None, &|_, _, _| {}).unwrap();
        for n in [1, 7, 1000] {
            let got = drive(&p, s, n);
            assert_eq!(got.all, want.all, "asked {n} at a time");
            assert_eq!(got.front, want.front);
            assert_eq!(got.reference, want.reference);
            assert_eq!(got.hypervolume, want.hypervolume);
            assert!(!got.partial);
        }
    }

    #[test]
    fn a_point_not_asked_or_told_twice_is_refused_and_an_unfinished_search_is_partial() {
        let p = problem(vec![]);
        let mut at = AskTell::new(p.clone(), Settings { evaluations: 20, seed: 1 }, None).unwrap();
        let xs = at.ask(3).unwrap();
        assert_eq!(xs.len(), 3);
        assert_eq!(at.outstanding(), 3);
        let stranger = vec![Value::Number(0.05), Value::Number(0.123_456)];
        assert_eq!(at.tell(&stranger, Ok(vec![Some(1.0), Some(1.0)])).unwrap_err().param(), "tell");
        assert!(at.tell(&xs[0], Ok(vec![Some(1.0)])).is_err(), "one value for two columns");
        at.tell(&xs[0], Ok(vec![Some(100.0), Some(1.0)])).unwrap();
        assert!(at.tell(&xs[0], Ok(vec![Some(100.0), Some(1.0)])).is_err(), "told twice");
        assert!(at.outcome().partial && at.outcome().all.is_empty(), "the batch is not told yet");
        assert!(!at.done());
    }
}
