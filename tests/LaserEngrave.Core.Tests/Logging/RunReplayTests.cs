using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Logging;

public sealed class RunReplayTests : IDisposable
{
    private readonly TestRuns runs = new();

    [Fact]
    public void ToJobSpec_ImageUnchanged_GivesTheSameJobBack()
    {
        var logged = RunRecordJson.Deserialize(RunRecordJson.Serialize(runs.FailedRecord()), "test");

        var spec = RunReplay.ToJobSpec(logged);

        Assert.Equal(runs.Spec() with { ImagePath = Path.GetFullPath(runs.ImagePath) }, spec);
        var again = PreparedJob.Prepare(spec);
        var original = PreparedJob.Prepare(runs.Spec());
        Assert.Equal(original.Statistics, again.Statistics);
        Assert.Equal(original.Geometry.Geometry, again.Geometry.Geometry);
    }

    [Fact]
    public void ToJobSpec_TurnedMirroredRun_TheSameTurnedMaskAgainAndOldLogsUpright()
    {
        var first = runs.FailedRecord();
        var record = first with { Mask = first.Mask with { QuarterTurns = 1, MirrorX = true } };
        var logged = RunRecordJson.Deserialize(RunRecordJson.Serialize(record), "test");

        var again = PreparedJob.Prepare(RunReplay.ToJobSpec(logged));

        Assert.Equal(record.Mask, logged.Mask);
        var upright = PreparedJob.Prepare(runs.Spec()).Mask;
        Assert.True(again.Mask.ContentEquals(MaskOrientation.Apply(upright, record.Mask)));

        // A log written before the turn existed has no such members: upright, as it ran.
        var old = System.Text.Json.Nodes.JsonNode.Parse(RunRecordJson.Serialize(runs.FailedRecord()))!.AsObject();
        var mask = old["mask"]!.AsObject();
        mask.Remove("quarterTurns");
        mask.Remove("mirrorX");
        mask.Remove("mirrorY");
        Assert.Equal(first.Mask, RunRecordJson.Deserialize(old.ToJsonString(), "old").Mask);
        Assert.False(first.Mask.Transforms);
    }

    [Fact]
    public void ToJobSpec_ImageChanged_RefusesNamingTheImage()
    {
        var record = runs.FailedRecord();
        File.AppendAllText(runs.ImagePath, "x");

        var ex = Assert.Throws<RunLogException>(() => RunReplay.ToJobSpec(record));

        Assert.StartsWith($"{Path.GetFullPath(runs.ImagePath)}: the image has changed since the run", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void ToJobSpec_ImageMoved_RefusesSayingItIsNotThere()
    {
        var record = runs.FailedRecord();
        File.Move(runs.ImagePath, runs.ImagePath + ".moved");

        var ex = Assert.Throws<RunLogException>(() => RunReplay.ToJobSpec(record));

        Assert.Contains("not there any more", ex.Message, StringComparison.Ordinal);
    }

    public static TheoryData<SizeSpec> Sizes() =>
    [
        SizeSpec.Width(5),
        SizeSpec.Height(4.5),
        SizeSpec.WidthAndHeight(5, 5),
        SizeSpec.Pitch(40),
        SizeSpec.Resolution(600),
    ];

    [Theory]
    [MemberData(nameof(Sizes))]
    public void RunSize_EveryKind_RoundTripsToTheSameSizeSpec(SizeSpec size)
    {
        Assert.Equal(size, RunSize.From(size).ToSizeSpec());
    }

    [Fact]
    public void RunSize_ValueOfItsKindMissing_Throws()
    {
        var ex = Assert.Throws<RunLogException>(() => new RunSize(RunSizeKind.Pitch, WidthMm: 5).ToSizeSpec());

        Assert.Contains("pitchUm is missing", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Check_GoodLog_NoProblem()
    {
        Assert.Null(RunReplay.Problem(runs.FailedRecord()));
    }

    [Fact]
    public void ToJobSpec_OverscanPastTheTravel_RefusedBeforeAnythingMoves()
    {
        var record = runs.FailedRecord();
        var bad = record with { Plan = record.Plan with { OverscanMm = 1e308 } };

        var ex = Assert.Throws<RunLogException>(() => RunReplay.ToJobSpec(bad, "runs/a.json"));

        Assert.Equal("runs/a.json: plan.overscanMm 1E+308: must be 0..60 mm (the X travel)", ex.Message);
    }

    [Fact]
    public void ToJobSpec_StopRowNegative_RefusedNamingTheField()
    {
        var record = runs.FailedRecord() with { StoppedAt = new RunStopPoint(-1, 0) };

        var ex = Assert.Throws<RunLogException>(() => RunReplay.ToJobSpec(record, "runs/a.json"));

        Assert.Equal("runs/a.json: stoppedAt.row -1 must not be negative", ex.Message);
    }

    [Fact]
    public void ToJobSpec_PassesOutOfRange_RefusedNotClamped()
    {
        var record = runs.FailedRecord() with { Passes = 1000 };

        var ex = Assert.Throws<RunLogException>(() => RunReplay.ToJobSpec(record, "runs/a.json"));

        Assert.Equal("runs/a.json: passes 1000: must be 1..100 (burns of the plan over the same place)", ex.Message);
    }

    public void Dispose() => runs.Dispose();
}
