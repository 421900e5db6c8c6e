using BenchmarkDotNet.Attributes;
using BenchmarkDotNet.Configs;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Benchmarks;

/// <summary>Plan statistics (runs, lengths, estimated time) of a 20000 x 20000 QR-like mask; the Gpx/s column is the planning throughput.</summary>
[Config(typeof(Config))]
[MemoryDiagnoser]
public class PlanStatisticsBenchmark
{
    public const int Side = 20_000;

    private BitMask _mask = null!;
    private JobGeometry _geometry = null!;

    [GlobalSetup]
    public void Setup()
    {
        _mask = QrLikeMask.Create(Side);
        _geometry = GeometryResolver.Resolve(SizeSpec.Width(50), Side, Side, new OriginMm(5, 5), MachineProfile.Default).Geometry;
    }

    [Benchmark(Baseline = true)]
    public PlanStatistics Optimized() => new RasterPlan(_mask, _geometry).ComputeStatistics(ProcessSettings.Default);

    [Benchmark]
    public PlanStatistics OptimizedWithOverscan() =>
        new RasterPlan(_mask, _geometry, new PlanOptions { OverscanMm = 0.2 }).ComputeStatistics(ProcessSettings.Default);

    [Benchmark]
    public PlanStatistics Paper() =>
        new RasterPlan(_mask, _geometry, new PlanOptions { Strategy = PlanStrategy.Paper }).ComputeStatistics(ProcessSettings.Default);

    private sealed class Config : ManualConfig
    {
        public Config() => AddColumn(new GigapixelsPerSecondColumn((long)Side * Side));
    }
}
