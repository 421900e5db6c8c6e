using System.Text.Json;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Logging;

public sealed class RunRecordJsonTests : IDisposable
{
    private readonly TestRuns runs = new();

    [Fact]
    public void Deserialize_SerializedRecord_GivesTheSameRecordBack()
    {
        var record = runs.FailedRecord();

        var json = RunRecordJson.Serialize(record);
        var back = RunRecordJson.Deserialize(json, "test");

        Assert.Equal(json, RunRecordJson.Serialize(back));
        Assert.Equal(record with { Devices = back.Devices }, back);
        Assert.Equal(record.Devices, back.Devices);
    }

    [Fact]
    public void Serialize_Record_HasSchemaVersionTimesWithOffsetAndCamelCaseEnums()
    {
        using var json = JsonDocument.Parse(RunRecordJson.Serialize(runs.FailedRecord()));
        var root = json.RootElement;

        Assert.Equal(RunRecord.CurrentSchemaVersion, root.GetProperty("schemaVersion").GetInt32());
        Assert.Equal("2026-11-23T14:30:05.123+02:00", root.GetProperty("startedAt").GetString());
        Assert.Equal("2026-11-23T14:31:06.623+02:00", root.GetProperty("endedAt").GetString());
        Assert.Equal("failed", root.GetProperty("outcome").GetString());
        Assert.Equal("floydSteinberg", root.GetProperty("mask").GetProperty("dither").GetString());
        Assert.Equal("optimized", root.GetProperty("plan").GetProperty("strategy").GetString());
        Assert.Equal("width", root.GetProperty("geometry").GetProperty("size").GetProperty("by").GetString());
    }

    [Fact]
    public void RoundTrip_StopPointCutMidRun_KeepsWhereToResumeAndThePixelBurnedTwice()
    {
        var stop = new RunStopPoint(3, 17) { ResumeXMicrosteps = 12_345, CutPixel = new PixelIndex(7, 3), ExpectedXMicrosteps = 20_000 };
        var record = runs.FailedRecord() with { StoppedAt = stop };

        var back = RunRecordJson.Deserialize(RunRecordJson.Serialize(record), "test");

        Assert.Equal(stop, back.StoppedAt);
        var text = RunSummaryText.Format(back);
        Assert.Contains("Resumes:            mid-run at X 12345 microsteps if X is found at 20000 microsteps (else from the run's start); pixel column 7, row 3 (the laser went off in it) burns twice", text, StringComparison.Ordinal);
    }

    [Fact]
    public void Serialize_Record_HoldsEveryFieldTheIssueLists()
    {
        var record = runs.FailedRecord();
        using var json = JsonDocument.Parse(RunRecordJson.Serialize(record));
        var root = json.RootElement;

        Assert.Equal(RunRecord.CurrentSoftwareVersion, root.GetProperty("softwareVersion").GetString());
        Assert.Equal("timeout", root.GetProperty("fault").GetProperty("kind").GetString());
        Assert.Equal(40, root.GetProperty("stoppedAt").GetProperty("moveIndex").GetInt64());
        Assert.Equal(PreparedJob.HashFile(runs.ImagePath), root.GetProperty("image").GetProperty("sha256").GetString());
        Assert.Equal(record.Image.WidthPx, root.GetProperty("image").GetProperty("widthPx").GetInt32());
        Assert.Equal(42, root.GetProperty("mask").GetProperty("thresholdPercent").GetDouble());
        var geometry = root.GetProperty("geometry");
        Assert.Equal(record.Geometry.PitchUm, geometry.GetProperty("pitchUm").GetDouble());
        Assert.Equal(record.Geometry.MicrostepsPerPixel, geometry.GetProperty("microstepsPerPixel").GetDouble());
        Assert.Equal(10.5, geometry.GetProperty("originXMm").GetDouble());
        Assert.Equal(5, geometry.GetProperty("size").GetProperty("widthMm").GetDouble());
        Assert.Equal(0.2, root.GetProperty("plan").GetProperty("overscanMm").GetDouble());
        var process = root.GetProperty("process");
        Assert.Equal(0.8, process.GetProperty("burnSpeedMmPerS").GetDouble());
        Assert.Equal(3, process.GetProperty("travelSpeedMmPerS").GetDouble());
        Assert.Equal(40, process.GetProperty("accelerationMmPerS2").GetDouble());
        Assert.Equal(1500, process.GetProperty("laserFrequencyHz").GetDouble());
        Assert.Equal(record.Profile.Name, root.GetProperty("profile").GetProperty("name").GetString());
        Assert.Equal("5.29", root.GetProperty("devices")[0].GetProperty("firmware").GetString());
        Assert.Equal(record.EstimatedSeconds, root.GetProperty("estimatedSeconds").GetDouble());
        Assert.Equal(61.5, root.GetProperty("actualSeconds").GetDouble());
        Assert.Equal(55.5, root.GetProperty("engravingSeconds").GetDouble());
        Assert.Equal(20.25, root.GetProperty("laserOnSeconds").GetDouble());
        Assert.Equal(11, root.GetProperty("rowsDone").GetInt32());
        Assert.Equal(40, root.GetProperty("runsDone").GetInt64());
        Assert.Equal("first try\nfocus 2 turns down", root.GetProperty("notes").GetString());
        Assert.Equal("S-17", root.GetProperty("sampleId").GetString());
    }

    [Fact]
    public void Serialize_NotesWithAccentsAndAVersionWithPlus_WrittenAsTyped()
    {
        var json = RunRecordJson.Serialize(runs.FailedRecord() with { Notes = "Probe µ-3, réglage", SoftwareVersion = "0.1.0+abc" });

        Assert.Contains("\"notes\": \"Probe µ-3, réglage\"", json, StringComparison.Ordinal);
        Assert.Contains("\"softwareVersion\": \"0.1.0+abc\"", json, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("{", "not a run log")]
    [InlineData("null", "not a run log")]
    [InlineData("[]", "not a run log")]
    public void Deserialize_NotARecord_ThrowsOneLineNamingTheSource(string json, string expected)
    {
        var ex = Assert.Throws<RunLogException>(() => RunRecordJson.Deserialize(json, "runs/a.json"));

        Assert.StartsWith("runs/a.json: " + expected, ex.Message, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', ex.Message);
    }

    [Theory]
    [InlineData("\"sha256\"")]
    [InlineData("\"outcome\"")]
    [InlineData("\"image\"")]
    public void Deserialize_RequiredValueMissing_Throws(string property)
    {
        var json = RunRecordJson.Serialize(runs.FailedRecord());
        var renamed = json.Replace(property, "\"renamed\"", StringComparison.Ordinal);

        var ex = Assert.Throws<RunLogException>(() => RunRecordJson.Deserialize(renamed, "x.json"));

        Assert.StartsWith("x.json: not a run log", ex.Message, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', ex.Message);
    }

    [Fact]
    public void Deserialize_NewerSchemaVersion_RefusesNamingTheVersion()
    {
        var json = RunRecordJson.Serialize(runs.FailedRecord() with { SchemaVersion = RunRecord.CurrentSchemaVersion + 1 });

        var ex = Assert.Throws<RunLogException>(() => RunRecordJson.Deserialize(json, "x.json"));

        Assert.Contains($"schema version {RunRecord.CurrentSchemaVersion + 1}", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void ForJob_PreparedJob_TakesImageGeometryAndTotalsFromIt()
    {
        var job = PreparedJob.Prepare(runs.Spec());

        var record = RunRecord.ForJob(job, "abc", TestRuns.Start);

        Assert.Equal(RunOutcome.Failed, record.Outcome);
        Assert.Equal(Path.GetFullPath(runs.ImagePath), record.Image.Path);
        Assert.Equal((job.Mask.Width, job.Mask.Height), (record.Image.WidthPx, record.Image.HeightPx));
        Assert.Equal(job.Geometry.PitchUm, record.Geometry.PitchUm);
        Assert.Equal(job.Geometry.AchievedWidthMm, record.Geometry.WidthMm);
        Assert.Equal(job.Statistics.Rows, record.RowsTotal);
        Assert.Equal(job.Statistics.BurnRuns, record.RunsTotal);
        Assert.Equal(job.Statistics.WholeRunSeconds(), record.EstimatedSeconds);
        Assert.Equal(job.Statistics.EngravingSeconds, record.EstimatedEngravingSeconds);
        Assert.True(record.EstimatedSeconds > record.EstimatedEngravingSeconds, "the whole run includes preflight and homing");
        Assert.Same(job.Spec.Process, record.Process);
    }

    public void Dispose() => runs.Dispose();
}
