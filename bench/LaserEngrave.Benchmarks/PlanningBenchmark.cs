using BenchmarkDotNet.Attributes;
using BenchmarkDotNet.Configs;
using BenchmarkDotNet.Jobs;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Benchmarks;

/// <summary>
/// Plan generation and the estimate of a 20000 x 20000 mask planned as `laserengrave plan MASK --width-mm 50 --origin-mm 5,5`
/// does it (optimized, timed switching): the rings (13 M moves, every gap flown) and the QR-like mask (460 k moves).
/// </summary>
/// <remarks>
/// <see cref="Moves"/> generates every move; <see cref="Program"/> makes the program's steps from them (strokes planned);
/// <see cref="Estimate"/> interprets that program and <see cref="LowerBoundOnly"/> feeds the moves to the bound, so the
/// difference to the one before is that consumer's cost; <see cref="Statistics"/> is the whole
/// pass `plan` makes. A fresh timing model each time, so that no answer is remembered from the iteration before.
/// </remarks>
[Config(typeof(Config))]
[MemoryDiagnoser]
public class PlanningBenchmark
{
    public const int Side = 20_000;

    private BitMask _mask = null!;
    private JobGeometry _geometry = null!;
    private ProcessSettings _process = null!;

    [Params("rings", "qr-like")]
    public string Mask { get; set; } = "rings";

    [GlobalSetup]
    public void Setup()
    {
        _mask = Mask == "rings" ? RingsMask.Create(Side) : QrLikeMask.Create(Side);
        _geometry = GeometryResolver.Resolve(SizeSpec.Width(50), Side, Side, new OriginMm(5, 5), MachineProfile.Default).Geometry;
        _process = ProcessSettings.Default;
    }

    [Benchmark(Baseline = true)]
    public long Moves()
    {
        var counter = default(MoveCounter);
        Plan().Visit(ref counter);
        return counter.Count;
    }

    /// <summary>The program (travels and strokes, each stroke planned with its flown gaps) made from the moves, read by a counter.</summary>
    [Benchmark]
    public long Program()
    {
        var counter = default(StepCounter);
        new RasterProgram(Plan(), _process).Visit(ref counter);
        return counter.Count;
    }

    /// <summary>The program interpreted against the motion model, as the plan's estimate is made.</summary>
    [Benchmark]
    public double Estimate()
    {
        var program = new RasterProgram(Plan(), _process);
        var estimator = new EstimatingVisitor(new PlanEstimator(program));
        program.Visit(ref estimator);
        estimator.Estimator.Finish();
        return estimator.Estimator.ElapsedSeconds;
    }

    [Benchmark]
    public double LowerBoundOnly()
    {
        var bound = new BoundingVisitor(new LowerBound(_process, _geometry.MicrostepUm));
        Plan().Visit(ref bound);
        return bound.Bound.Seconds;
    }

    [Benchmark]
    public PlanStatistics Statistics() => Plan().ComputeStatistics(_process);

    private RasterPlan Plan() => new(_mask, _geometry, PlanOptions.Default, 0, TimedSwitching.For(_process, MachineProfile.Default, _geometry.MicrostepUm));

    private struct MoveCounter : IMoveVisitor
    {
        public long Count;

        public void Visit(in Move move) => Count++;
    }

    private struct StepCounter : IRasterStepVisitor
    {
        public long Count;

        public void Travel(in TravelStep travel) => Count++;

        public void Stroke(StrokeStep stroke) => Count++;

        public void Move(in MoveStep move) => Count++;
    }

    private readonly struct EstimatingVisitor(PlanEstimator estimator) : IRasterStepVisitor
    {
        public readonly PlanEstimator Estimator = estimator;

        public void Travel(in TravelStep travel) => Estimator.Travel(travel);

        public void Stroke(StrokeStep stroke) => Estimator.Stroke(stroke);

        public void Move(in MoveStep move) => Estimator.Move(move);
    }

    private struct BoundingVisitor(LowerBound bound) : IMoveVisitor
    {
        public LowerBound Bound = bound;

        public void Visit(in Move move) => Bound.Add(move);
    }

    private sealed class Config : ManualConfig
    {
        // A few iterations: one takes a second, and the machine it runs on is shared.
        public Config()
        {
            AddJob(Job.Default.WithLaunchCount(1).WithWarmupCount(2).WithIterationCount(7));
            AddColumn(new GigapixelsPerSecondColumn((long)Side * Side));
        }
    }
}
