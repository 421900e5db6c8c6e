using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Tests.Imaging;
using LaserEngrave.Core.Tests.Planning;

namespace LaserEngrave.Core.Tests.Programs;

/// <summary>
/// A resume found from the plan's row index and its estimate from the program's row estimates give, at every move of a
/// plan, what walking the whole plan gave (the code before the index, kept here as the reference).
/// </summary>
public sealed class RasterResumeIndexTests
{
    private static readonly ProcessSettings Process = ProcessSettings.Default;

    public static TheoryData<string> Plans => ["timed bidirectional", "timed unidirectional", "paper", "qr timed"];

    [Theory]
    [MemberData(nameof(Plans))]
    public void ResumeAtAndEstimateResumed_StopPoints_AsWalkingTheWholePlan(string name)
    {
        var plan = Plan(name);
        var program = new RasterProgram(plan, Process);
        var moves = plan.Moves().ToList();

        // Every stop point of the small plans; of the QR's 633 moves every 11th and the end (the reference walks the whole plan each time).
        var stride = name == "qr timed" ? 11 : 1;
        foreach (var i in Enumerable.Range(0, moves.Count + 1).Where(i => i % stride == 0 || i == moves.Count))
        {
            var row = i < moves.Count ? moves[i].Row : moves[^1].Row;
            long? resumeX = i < moves.Count && moves[i] is { Kind: MoveKind.Burn } burn && Math.Abs(burn.X1 - burn.X0) > 2 ? (burn.X0 + burn.X1) / 2 : null;
            foreach (var x in resumeX is null ? new long?[] { null } : [null, resumeX])
            {
                var stop = new RunStopPoint(row, i);
                var expected = Reference(plan, moves, stop, x);

                var resume = program.ResumeAt(stop, x);
                var estimate = program.EstimateResumed(resume);

                Assert.Equal(expected, resume);
                Assert.Equal(ReferenceEstimate(program, resume), estimate);
                Assert.Equal(moves.Skip(checked((int)resume.FirstMoveIndex)).Select((m, k) => k == 0 && x is { } cut ? m with { X0 = cut } : m), program.Steps(resume).SelectMany(StepMoves));
            }
        }
    }

    [Fact]
    public void ResumeAt_StopPointOfAnotherPlan_ThrowsAsBefore()
    {
        var plan = Plan("timed bidirectional");
        var program = new RasterProgram(plan, Process);
        var count = plan.Moves().Count();

        var negative = Assert.Throws<PlanException>(() => program.ResumeAt(new RunStopPoint(0, -1), null));
        var beyond = Assert.Throws<PlanException>(() => program.ResumeAt(new RunStopPoint(0, count + 1), null));
        var rowAfter = Assert.Throws<PlanException>(() => program.ResumeAt(new RunStopPoint(5, 1), null));

        Assert.Equal($"the resume point (row 0, move -1) is not in this job's plan of {count} moves", negative.Message);
        Assert.Equal($"the resume point (row 0, move {count + 1}) is not in this job's plan of {count} moves", beyond.Message);
        Assert.Equal($"the resume point (row 5, move 1) is not in this job's plan of {count} moves", rowAfter.Message);
    }

    private static RasterPlan Plan(string name)
    {
        if (name == "qr timed")
        {
            return PreparedJob.Prepare(new JobSpec
            {
                ImagePath = StarterAssetsTests.Asset("qr-code.bmp"),
                Size = SizeSpec.Width(2),
                Origin = new OriginMm(5, 5),
            }).Plan;
        }

        var mask = TestMasks.FromRows("..##......##..", "..............", "...##....##...", ".#.#.#.#.#.#.#", "..............", "######....####");
        var geometry = TestMasks.Geometry(mask, 4000, ox: 2_000_000, oy: 100_000);
        return name switch
        {
            "paper" => new RasterPlan(mask, geometry, new PlanOptions { Strategy = PlanStrategy.Paper }),
            _ => new RasterPlan(mask, geometry, new PlanOptions { Bidirectional = name == "timed bidirectional" }, 0, TimedSwitching.For(Process, MachineProfile.Default, TestMasks.Microstep)),
        };
    }

    // RasterProgram.ResumeAt before the row index: two walks over the whole plan.
    private static RasterResume Reference(RasterPlan plan, List<Move> moves, RunStopPoint stop, long? resumeX)
    {
        var start = stop.MoveIndex;
        Move? trimmed = null;
        if (stop.MoveIndex >= 0 && stop.MoveIndex < moves.Count)
        {
            var move = moves[(int)stop.MoveIndex];
            var previous = stop.MoveIndex > 0 ? moves[(int)stop.MoveIndex - 1] : (Move?)null;
            if (resumeX is { } x)
            {
                trimmed = move with { X0 = x };
            }
            else if (move.Kind == MoveKind.Burn && previous is { Kind: MoveKind.Overscan } runUp && runUp.Row == move.Row)
            {
                start--;
            }
        }

        long rowStart = -1, runs = 0;
        int rows = 0, lastRow = -1;
        for (var index = 0; index < moves.Count; index++)
        {
            var move = moves[index];
            if (rowStart < 0 && move.Row >= stop.Row)
            {
                rowStart = index;
            }

            if (index < start)
            {
                runs += move.Kind == MoveKind.Burn ? 1 : 0;
                if (move.Row != lastRow)
                {
                    rows += lastRow >= 0 ? 1 : 0;
                    lastRow = move.Row;
                }
            }
        }

        return new RasterResume(stop, start, trimmed, rowStart, plan.Moves().LongCount(), runs, rows, lastRow);
    }

    // RasterProgram.EstimateResumed before the row estimates: the whole program up to the resume point, then its steps after.
    private static (double Before, double Remaining) ReferenceEstimate(RasterProgram program, RasterResume from)
    {
        var before = new BeforeVisitor(new PlanEstimator(program), from.FirstMoveIndex);
        program.Visit(ref before);
        var remaining = new PlanEstimator(program);
        foreach (var step in program.Steps(from))
        {
            _ = step.Stroke is { } stroke ? remaining.Stroke(stroke) : step.IsTravel ? remaining.Travel(step.Travel) : remaining.Move(step.Move);
        }

        remaining.Finish();
        return (before.Seconds, remaining.ElapsedSeconds);
    }

    private static IEnumerable<Move> StepMoves(RasterStep step) =>
        step.Stroke is { } stroke ? Enumerable.Range(0, stroke.MoveCount).Select(stroke.MoveAt)
        : step.IsTravel ? [step.Travel.Move]
        : [step.Move.Move];

    private struct BeforeVisitor(PlanEstimator estimator, long firstIndex) : IRasterStepVisitor
    {
        public double Seconds { get; private set; }

        public void Travel(in TravelStep travel)
        {
            if (travel.MoveIndex < firstIndex)
            {
                estimator.Travel(travel);
                Seconds = estimator.ElapsedSeconds - estimator.StartSeconds;
            }
        }

        public void Stroke(StrokeStep stroke)
        {
            var end = stroke.FirstMoveIndex + stroke.MoveCount;
            if (end < firstIndex)
            {
                estimator.Stroke(stroke);
                Seconds = estimator.ElapsedSeconds - estimator.StartSeconds;
            }
            else if (stroke.FirstMoveIndex < firstIndex)
            {
                Seconds = estimator.Provisional(stroke, checked((int)(firstIndex - stroke.FirstMoveIndex))) - estimator.StartSeconds;
            }
        }

        public void Move(in MoveStep move)
        {
            if (move.MoveIndex < firstIndex)
            {
                estimator.Move(move);
                Seconds = estimator.ElapsedSeconds - estimator.StartSeconds;
            }
        }
    }
}
