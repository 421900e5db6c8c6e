using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;
using Microsoft.Extensions.Time.Testing;
using NSubstitute;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Dot mode's motion alone (<see cref="DotMotion"/>): a resumed run's dots before counted, a resume point outside the plan refused.</summary>
public class DotMotionTests
{
    private static readonly ProcessSettings DotProcess = ProcessSettings.Default with { Mode = PlanMode.Dots, PulsesPerDot = 2 };

    [Fact]
    public void Prepare_ResumePointPastTheLastDot_RefusedBeforeAnythingMoves()
    {
        var program = Program(out var dots);
        var run = new FakeRun(new RunOptions { ResumeFrom = new RunStopPoint(0, dots + 1) });

        var ex = Assert.Throws<PreflightException>(() => new DotMotion(run, program).Prepare());

        Assert.EndsWith($"is not in this job's plan of {dots} dots", ex.Message, StringComparison.Ordinal);
        Assert.Empty(run.Moves);
    }

    [Fact]
    public void Prepare_ResumedAtTheThirdDot_CountsTheTwoBeforeAsBurned()
    {
        var program = Program(out _);
        var run = new FakeRun(new RunOptions { ResumeFrom = new RunStopPoint(0, 2) });

        new DotMotion(run, program).Prepare();

        Assert.Equal(2, run.Accounting.RunsDone);
        Assert.Equal(program.SecondsBefore(2), run.Accounting.EstimateBefore, 12);
    }

    private static DotProgram Program(out long dots)
    {
        var job = TestJobs.FromMask(TestJobs.RandomMask(seed: 31, 6, 3), 1, new PlanOptions(), process: DotProcess);
        dots = job.Dots!.Estimate.Dots;
        return job.Dots.Program();
    }

    private sealed class FakeRun(RunOptions options) : IRunMotion
    {
        private readonly FakeTimeProvider _time = new();

        public RunOptions Options { get; } = options;

        public TimeProvider TimeProvider => _time;

        public ILaserGate Gate { get; } = Substitute.For<ILaserGate>();

        public LaserSafety Laser => field ??= new LaserSafety(Gate, _time, 1000, 1000, 20, new NoRun());

        public RunAccounting Accounting { get; } = new(100, 100);

        public ProcessSettings Process => DotProcess;

        public MachineProfile Profile => MachineProfile.Default;

        public bool Homed => true;

        public (long X, long Y) Position => (0, 0);

        public List<(long X, long Y)> Moves { get; } = [];

        public List<long> Completions { get; } = [];

        public Task BeginEngravingAsync(long firstIndex, int row, CancellationToken token) => Task.CompletedTask;

        public Task MoveToAsync(long x, long y, int speedData, CancellationToken token)
        {
            Moves.Add((x, y));
            return Task.CompletedTask;
        }

        public Task PauseIfAskedAsync(CancellationToken token) => Task.CompletedTask;

        public void Completed(Move move, long index) => Completions.Add(index);

        public void ThrowIfAborted()
        {
        }

        public void NotEngraving(TimeSpan spent)
        {
        }
    }

    private sealed class NoRun : ILaserSafetyRun
    {
        public TimedSwitching Timing => TimedSwitching.For(DotProcess, MachineProfile.Default, MachineProfile.Default.X.MicrostepUm);

        public double GateQueueSeconds => 0;

        public void ThrowIfAborted()
        {
        }

        public void OffSequenceStarting(bool? inDoubt)
        {
        }

        public Task StopStageAsync() => Task.CompletedTask;
    }
}
