using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Logging;

/// <summary>A temporary folder holding a copy of the QR sample, and run records of jobs on it.</summary>
internal sealed class TestRuns : IDisposable
{
    public TestRuns()
    {
        Folder = Path.Combine(Path.GetTempPath(), $"le-log-{Guid.NewGuid():N}");
        Directory.CreateDirectory(Folder);
        ImagePath = Path.Combine(Folder, "qr-code.bmp");
        File.Copy(Asset("qr-code.bmp"), ImagePath);
    }

    public string Folder { get; }

    public string ImagePath { get; }

    public static DateTimeOffset Start { get; } = new(2026, 11, 23, 14, 30, 5, 123, TimeSpan.FromHours(2));

    public JobSpec Spec() => new()
    {
        ImagePath = ImagePath,
        Mask = new MaskOptions { ThresholdPercent = 42, Dither = DitherMethod.FloydSteinberg, Invert = true },
        Size = SizeSpec.Width(5),
        Origin = new OriginMm(10.5, 7.25),
        Plan = new PlanOptions { Strategy = PlanStrategy.Optimized, Bidirectional = false, OverscanMm = 0.2 },
        Process = ProcessSettings.Default with { BurnSpeedMmPerS = 0.8, TravelSpeedMmPerS = 3, AccelerationMmPerS2 = 40, LaserFrequencyHz = 1500 },
    };

    /// <summary>A failed run of <see cref="Spec"/> with every optional field set.</summary>
    public RunRecord FailedRecord(string? sample = "S-17")
    {
        var job = PreparedJob.Prepare(Spec());
        return RunRecord.ForJob(job, PreparedJob.HashFile(ImagePath), Start) with
        {
            EndedAt = Start.AddSeconds(61.5),
            Outcome = RunOutcome.Failed,
            Fault = new RunFault("x axis: no reply within 500 ms", "timeout", LaserOffConfirmed: true),
            StoppedAt = new RunStopPoint(12, 40, 123456, 98765),
            Simulated = true,
            Devices = [new RunDevice("x axis", "simulator", "device 1, ID 6320", "5.29"), new RunDevice("laser gate", "simulator", "CEILAP PIC gate v1.2", "1.2")],
            ActualSeconds = 61.5,
            EngravingSeconds = 55.5,
            EstimatedSeconds = 70.3,
            EstimatedEngravingSeconds = 54.8,
            LaserOnSeconds = 20.25,
            RowsDone = 11,
            RunsDone = 40,
            Notes = "first try\nfocus 2 turns down",
            SampleId = sample,
            RepeatOf = "/logs/2026-11-22_090000_S-16.json",
        };
    }

    public static string Asset(string name)
    {
        var folder = new DirectoryInfo(AppContext.BaseDirectory);
        while (folder is not null && !File.Exists(Path.Combine(folder.FullName, "LaserEngrave.sln")))
        {
            folder = folder.Parent;
        }

        Assert.NotNull(folder);
        return Path.Combine(folder.FullName, "assets", name);
    }

    public void Dispose() => Directory.Delete(Folder, recursive: true);
}
