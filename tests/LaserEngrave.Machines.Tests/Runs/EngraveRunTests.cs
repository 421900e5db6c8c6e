using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Machines.Runs;

namespace LaserEngrave.Machines.Tests.Runs;

/// <summary>The one run every front end starts: its checks before anything opens, and the run itself on the twin.</summary>
public sealed class EngraveRunTests : IDisposable
{
    private readonly string _folder = Directory.CreateTempSubdirectory("engrave-run-").FullName;

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    private string LogDir => Path.Combine(_folder, "logs");

    private string WriteImage(string name, Action<BitMask> draw)
    {
        var mask = new BitMask(20, 20);
        draw(mask);
        var path = Path.Combine(_folder, name);
        using var file = File.Create(path);
        BmpMaskWriter.Write(file, mask);
        return path;
    }

    private static PreparedJob Prepare(string image, double originXMm = 0) =>
        PreparedJob.Prepare(new JobSpec { ImagePath = image, Size = SizeSpec.Width(2), Origin = new OriginMm(originXMm, 0) });

    private EngraveRun Run(EngraveJob job, Action? checkWritable = null)
    {
        var store = new RunLogStore(LogDir);
        return new EngraveRun(new RunRequest { Job = job }, new RunLog(store, checkWritable ?? store.CheckWritable));
    }

    [Fact]
    public void Check_AllWhiteImage_RefusedNamingTheFileAndNothingToBurn()
    {
        var white = WriteImage("white.bmp", _ => { });

        var refusal = Run(Prepare(white)).Check();

        Assert.NotNull(refusal);
        Assert.Equal(RunRefusalReason.Unrunnable, refusal.Reason);
        Assert.StartsWith($"{white}: ", refusal.Message, StringComparison.Ordinal);
        Assert.Contains("no pixel to burn", refusal.Message, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', refusal.Message);
    }

    [Fact]
    public void Check_JobOutsideTheTravel_RefusedWithItsSizeOriginAndTheTravel()
    {
        var dot = WriteImage("dot.bmp", m => m[5, 5] = true);

        var refusal = Run(Prepare(dot, originXMm: 59.5)).Check();

        Assert.NotNull(refusal);
        Assert.Equal(RunRefusalReason.Unrunnable, refusal.Reason);
        Assert.Contains("at origin 59.5, 0 mm) does not fit the stage's travel (60 x 60 mm)", refusal.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Check_LogFolderTakesNoFile_RefusedWithTheLogsReason()
    {
        var dot = WriteImage("dot.bmp", m => m[5, 5] = true);

        var refusal = Run(Prepare(dot), () => throw new RunLogException("the log folder is read-only")).Check();

        Assert.NotNull(refusal);
        Assert.Equal(RunRefusalReason.LogNotWritable, refusal.Reason);
        Assert.Equal("the log folder is read-only", refusal.Message);
        Assert.IsType<RunLogException>(refusal.Cause);
    }

    [Fact]
    public void Check_RunnableJobAndWritableLog_NoRefusal()
    {
        var dot = WriteImage("dot.bmp", m => m[5, 5] = true);

        Assert.Null(Run(Prepare(dot)).Check());
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_OnTheTwin_CompletesAndWritesTheLog()
    {
        var ct = TestContext.Current.CancellationToken;
        var dot = WriteImage("dot.bmp", m => m[5, 5] = true);
        var run = Run(Prepare(dot));
        await using var opened = MachineFactory.OpenTwin(MachineProfile.Default);

        var session = run.Open(opened.Engraving, recorder: null);
        var end = await EngraveRun.RunAsync(session, null, ct);

        Assert.Equal(RunOutcome.Completed, end.Result.Record.Outcome);
        Assert.True(end.Result.Record.Simulated);
        Assert.NotNull(end.Result.Files);
        Assert.True(File.Exists(end.Result.Files.JsonPath));
        Assert.Null(end.NextMarkNumber);
        Assert.Null(end.CounterProblem);
    }
}
