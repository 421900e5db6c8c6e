using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Tests.Imaging;
using LaserEngrave.Core.Tests.Planning;

namespace LaserEngrave.Core.Tests.Programs;

/// <summary>The program of a raster pass: its strokes, travels and plain moves, resume from a stop point, and the estimate over it.</summary>
public class RasterProgramTests
{
    private static readonly ProcessSettings Process = ProcessSettings.Default;

    [Fact]
    public void Steps_TimedPlan_StrokesHoldTheirRowsRunsGapsAndRunUp()
    {
        var plan = Timed(TestMasks.FromRows("..###....###..", "..............", "#............#"), pitch: 4000);
        var program = new RasterProgram(plan, Process);
        var steps = program.Steps().ToList();
        var moves = plan.Moves().ToList();

        // Every move of the plan, once and in order, in the steps.
        Assert.Equal(moves, steps.SelectMany(StepMoves));
        var strokes = steps.Where(s => s.Stroke is not null).Select(s => s.Stroke!).ToList();
        Assert.NotEmpty(strokes);
        foreach (var stroke in strokes)
        {
            var own = Enumerable.Range(0, stroke.MoveCount).Select(stroke.MoveAt).ToList();
            Assert.Equal(moves[(int)stroke.FirstMoveIndex], own[0]);

            // The whole plan's strokes start where their run-up does, and end at their run-out's end, in one row.
            Assert.Equal(own[0].X0, stroke.StartX);
            Assert.Equal(own[^1].X1, stroke.EndX);
            Assert.All(own, m => Assert.Equal(own[0].Row, m.Row));
            Assert.All(own, m => Assert.NotEqual(MoveKind.Travel, m.Kind));
            Assert.Equal(MoveKind.Overscan, own[0].Kind);
            Assert.True(Math.Abs(own[1].X0 - own[0].X0) >= plan.Timing!.RunUpMicrosteps);

            // Its runs are its burn moves; its gaps the offsets between them; its edges timed on its plan.
            var burns = own.Where(m => m.Kind == MoveKind.Burn).ToList();
            Assert.Equal(burns, Enumerable.Range(0, stroke.RunCount).Select(k => stroke.RunAt(k).Move));
            Assert.Equal(
                burns.Zip(burns.Skip(1), (a, b) => (Math.Abs(a.X1 - stroke.StartX), Math.Abs(b.X0 - stroke.StartX))),
                stroke.Gaps.ToArray());
            Assert.Equal(stroke.Length, stroke.Plan.Length);
            Assert.Equal(stroke.Plan.TimeAt(Math.Abs(burns[0].X0 - stroke.StartX)), stroke.FirstEdgeSeconds);
            Assert.Equal(stroke.Plan.TimeAt(Math.Abs(burns[^1].X1 - stroke.StartX)), stroke.LastOffSeconds);
            for (var k = 0; k < stroke.RunCount; k++)
            {
                Assert.Equal(moves.IndexOf(stroke.RunAt(k).Move), stroke.RunAt(k).MoveIndex);
            }
        }

        // Travels carry their target and the travel speed's data.
        var travel = steps.First(s => s.IsTravel).Travel;
        Assert.Equal((travel.Move.X1, travel.Move.Y1), (travel.X, travel.Y));
        Assert.Equal(program.Motion.TravelSpeedData, travel.SpeedData);
        Assert.Equal(StageUnits.SpeedData(Process.TravelSpeedMmPerS, plan.Geometry.MicrostepUm), program.Motion.TravelSpeedData);
    }

    [Fact]
    public void Steps_PaperPlan_ArePlainMovesAtTheBurnSpeed()
    {
        var mask = TestMasks.FromRows("..##..", "#....#");
        var plan = new RasterPlan(mask, TestMasks.Geometry(mask, ox: 1_000_000), new PlanOptions { Strategy = PlanStrategy.Paper });
        var program = new RasterProgram(plan, Process);
        var steps = program.Steps().ToList();

        Assert.Null(program.Timing);
        Assert.All(steps, s => Assert.True(s.Stroke is null && !s.IsTravel));
        Assert.Equal(plan.Moves(), steps.Select(s => s.Move.Move));
        Assert.Equal(plan.Moves().Select(m => m.Kind == MoveKind.Burn), steps.Select(s => s.Move.LaserOn));
        Assert.All(steps, s => Assert.Equal(program.Motion.BurnSpeedData, s.Move.SpeedData));
        Assert.Equal(Enumerable.Range(0, steps.Count).Select(i => (long)i), steps.Select(s => s.Move.MoveIndex));
    }

    [Fact]
    public void Visit_ReusingItsBuffers_GivesTheStepsOfSteps()
    {
        var rng = new Random(2323);
        for (var iteration = 0; iteration < 20; iteration++)
        {
            var mask = TestMasks.Random(rng, 20 + rng.Next(200), 1 + rng.Next(20));
            var plan = Timed(mask, pitch: 50 + (rng.NextDouble() * 2000));
            var program = new RasterProgram(plan, Process);
            var visited = new Recorder();
            program.Visit(ref visited);

            Assert.Equal(program.Steps().Select(Describe), visited.Steps);
        }
    }

    [Fact]
    public void ResumeAt_MidRunWithResumeX_FirstStrokeStartsARunUpBeforeIt()
    {
        var plan = Timed(TestMasks.FromRows("..........", "..######..", ".........."), pitch: 4000);
        var program = new RasterProgram(plan, Process);
        var moves = plan.Moves().ToList();
        var burnIndex = moves.FindIndex(m => m.Kind == MoveKind.Burn);
        var burn = moves[burnIndex];
        var resumeX = plan.Geometry.RunEdgeX(5, burn.Row, 0);

        var resume = program.ResumeAt(new RunStopPoint(burn.Row, burnIndex) { ResumeXMicrosteps = resumeX }, resumeX);
        var first = program.Steps(resume).First().Stroke!;

        // As the executor made it: the run from the resume X, a run-up before it within the travel, the rest of the row after it.
        var dir = Math.Sign(burn.X1 - burn.X0);
        Assert.Equal(burnIndex, resume.FirstMoveIndex);
        Assert.Equal(burn with { X0 = resumeX }, first.RunAt(0).Move);
        Assert.Equal(burnIndex, first.RunAt(0).MoveIndex);
        Assert.Equal(Math.Clamp(resumeX - (dir * plan.Timing!.RunUpMicrosteps), 0, plan.Geometry.TravelXMicrosteps), first.StartX);
        Assert.Equal(moves[^1].X1, first.EndX);
        Assert.Equal(first.Plan.TimeAt(plan.Timing.RunUpMicrosteps), first.FirstEdgeSeconds);
        Assert.Equal(0, resume.RunsBefore);
        Assert.Equal(moves.Skip(burnIndex + 1), Enumerable.Range(1, first.MoveCount - 1).Select(first.MoveAt));
    }

    [Fact]
    public void ResumeAt_ABurnRunsStart_GoesOnFromItsRunUp()
    {
        var plan = Timed(TestMasks.FromRows("..##......##..", "...##....##..."), pitch: 4000);
        var program = new RasterProgram(plan, Process);
        var moves = plan.Moves().ToList();
        var burnIndex = moves.FindIndex(m => m.Kind == MoveKind.Burn && m.Row == 1);

        var resume = program.ResumeAt(new RunStopPoint(1, burnIndex), null);

        Assert.Equal(burnIndex - 1, resume.FirstMoveIndex);
        Assert.Equal(MoveKind.Overscan, moves[burnIndex - 1].Kind);
        Assert.Equal(moves.Take(burnIndex - 1).Count(m => m.Kind == MoveKind.Burn), resume.RunsBefore);
        Assert.Equal(1, resume.RowsBefore);
        Assert.Equal(1, resume.LastRowBefore);
        Assert.Equal(moves.Skip(burnIndex - 1), program.Steps(resume).SelectMany(StepMoves));
    }

    [Fact]
    public void ResumeAt_ResumeXOutsideTheRun_ThrowsPlanExceptionNamingThePoint()
    {
        var plan = Timed(TestMasks.FromRows("..####.."), pitch: 4000);
        var program = new RasterProgram(plan, Process);
        var moves = plan.Moves().ToList();
        var burnIndex = moves.FindIndex(m => m.Kind == MoveKind.Burn);

        var error = Assert.Throws<PlanException>(() => program.ResumeAt(new RunStopPoint(0, burnIndex), moves[burnIndex].X0));
        Assert.Equal($"the resume point (row 0, move {burnIndex}, X {moves[burnIndex].X0}) is not inside a burn run of this job's plan", error.Message);
        var beyond = Assert.Throws<PlanException>(() => program.ResumeAt(new RunStopPoint(0, moves.Count + 1), null));
        Assert.Equal($"the resume point (row 0, move {moves.Count + 1}) is not in this job's plan of {moves.Count} moves", beyond.Message);
    }

    [Fact]
    public void EstimateResumed_FromTheStart_IsTheWholeEstimate()
    {
        var plan = Timed(TestMasks.FromRows("..##......##..", "...##....##..."), pitch: 4000);
        var program = new RasterProgram(plan, Process);
        var (before, remaining) = program.EstimateResumed(program.ResumeAt(new RunStopPoint(0, 0), null));

        Assert.Equal(0, before);
        Assert.Equal(plan.ComputeStatistics(Process).EngravingSeconds, remaining, 12);
    }

    // Figures of `laserengrave plan assets/qr-code.bmp ... --json` on main d97593d, before the estimate read the program;
    // the optimized ones since 2026-11-29 with the default profile's gate processing of the reference firmware, 0.19 ms
    // instead of 0.5 ms (at d97593d: 104.90941843950115 and 61.50834555698273 s), and since issue 34 with room after each
    // position query for a scheduled switch-on's longer line and its slack (before: 104.81132126335625 and 61.435632577912855 s).
    [Theory]
    [InlineData(5.0, PlanStrategy.Optimized, true, 633, 568, 108.32964598630534)]
    [InlineData(5.0, PlanStrategy.Paper, true, 649, 568, 437.04732911283355)]
    [InlineData(2.0, PlanStrategy.Optimized, false, 633, 568, 63.690411459626787)]
    public void Estimate_QrSample_KeepsTheFiguresOfTheEstimateBeforeThePrograms(double widthMm, PlanStrategy strategy, bool bidirectional, long moves, long switches, double seconds)
    {
        var job = PreparedJob.Prepare(new JobSpec
        {
            ImagePath = StarterAssetsTests.Asset("qr-code.bmp"),
            Size = SizeSpec.Width(widthMm),
            Origin = new OriginMm(5, 5),
            Plan = new PlanOptions { Strategy = strategy, Bidirectional = bidirectional },
        });

        Assert.Equal(moves, job.Statistics.Moves);
        Assert.Equal(switches, job.Statistics.LaserSwitches);
        Assert.Equal(seconds, job.Statistics.EngravingSeconds);
    }

    private static RasterPlan Timed(Core.Imaging.BitMask mask, double pitch)
    {
        var geometry = TestMasks.Geometry(mask, pitch, ox: 2_000_000, oy: 100_000);
        return new RasterPlan(mask, geometry, PlanOptions.Default, 0, TimedSwitching.For(Process, MachineProfile.Default, TestMasks.Microstep));
    }

    private static IEnumerable<Move> StepMoves(RasterStep step) =>
        step.Stroke is { } stroke ? Enumerable.Range(0, stroke.MoveCount).Select(stroke.MoveAt)
        : step.IsTravel ? [step.Travel.Move]
        : [step.Move.Move];

    private static string Describe(RasterStep step) =>
        step.Stroke is { } s ? Describe(s) : step.IsTravel ? step.Travel.ToString() : step.Move.ToString();

    private static string Describe(StrokeStep s) =>
        $"stroke {s.FirstMoveIndex}+{s.MoveCount} {s.StartX}->{s.EndX} y {s.Y} runs {s.RunCount} gaps {string.Join(",", s.Gaps.ToArray())} "
        + $"edges {s.FirstEdgeSeconds:R}/{s.LastOffSeconds:R} duration {s.Plan.Duration:R} bumps {s.Plan.Bumps.Count}";

    private struct Recorder() : IRasterStepVisitor
    {
        public List<string> Steps { get; } = [];

        public readonly void Travel(in TravelStep travel) => Steps.Add(travel.ToString());

        public readonly void Stroke(StrokeStep stroke) => Steps.Add(Describe(stroke));

        public readonly void Move(in MoveStep move) => Steps.Add(move.ToString());
    }
}
