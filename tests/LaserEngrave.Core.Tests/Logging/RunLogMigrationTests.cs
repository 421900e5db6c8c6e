using System.Text.Json.Nodes;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Logging;

/// <summary>Issue 31 finding 7: a log of every schema version reads as one a run can be repeated and resumed from.</summary>
public sealed class RunLogMigrationTests
{
    public static TheoryData<string> Version1Logs => [.. Directory.GetFiles(FixtureFolder, "v1-*.json").Order(StringComparer.Ordinal)];

    private static string FixtureFolder => Path.Combine(Path.GetDirectoryName(TestRuns.Asset("x"))!, "..", "tests", "LaserEngrave.Cli.Tests", "Fixtures", "RunLogs");

    [Theory]
    [MemberData(nameof(Version1Logs))]
    public void Read_Version1Log_EveryValueUsableAndTheProfileAsProfileFilesGiveIt(string fixture)
    {
        var record = RunRecordJson.Deserialize(File.ReadAllText(fixture), fixture);

        Assert.Null(RunReplay.Problem(record));
        Assert.Equal((RunRecord.CurrentSchemaVersion, 1), (record.SchemaVersion, record.ReadFromSchemaVersion));
        // What --profile gives the logged profile's file (members left out take their defaults).
        var asProfileFile = MachineProfileFromFile(JsonNode.Parse(File.ReadAllText(fixture))!["profile"]!.ToJsonString());
        Assert.Equal(asProfileFile.ToJson(), record.Profile.ToJson());
        Assert.True(record.Passes >= 1);
        Assert.True(record.Process.PulsesPerDot >= 1);
    }

    [Fact]
    public void Read_FirstVersion1Log_FillsWhatThatProgramHadNoWordFor()
    {
        var record = RunLogStore.Read(Path.Combine(FixtureFolder, "v1-2026-11-23-6256678-failed.json"));

        Assert.Equal(MachineProfile.Default.Latency, record.Profile.Latency);
        Assert.Equal(MachineProfile.Default.Gate.MaxFrequencyHz, record.Profile.Gate.MaxFrequencyHz);
        Assert.Equal(MachineProfile.Default.EdgeToleranceUm, record.Profile.EdgeToleranceUm);
        Assert.Equal((PlanMode.Raster, 1, 1), (record.Process.Mode, record.Process.PulsesPerDot, record.Passes));
        Assert.Equal(new RunStopPoint(15, 191), record.StoppedAt);
    }

    [Fact]
    public void Read_CurrentVersionLackingASection_StaysStrict()
    {
        // Only an older version is filled in: a log of the current version is written whole, so a missing section is an edited file.
        var node = JsonNode.Parse(File.ReadAllText(Path.Combine(FixtureFolder, "v3-2026-11-29-e64073c-completed.json")))!;
        node["profile"]!.AsObject().Remove("latency");

        var record = RunRecordJson.Deserialize(node.ToJsonString(), "run.json");

        Assert.Equal("profile.latency must not be null: give the section or leave it out for the defaults", RunReplay.Problem(record));
    }

    [Theory]
    [InlineData("v1-2026-11-23-6256678-failed.json", 15, 191, false)]
    [InlineData("v1-2026-11-23-3748455-failed.json", 15, 191, false)]
    [InlineData("v1-2026-11-27-50f0c04-failed.json", 16, 246, true)]
    [InlineData("v1-2026-11-29-17fa7f5-failed.json", 13, 190, true)]
    [InlineData("v2-2026-11-29-i31-log-failed.json", 13, 190, true)]
    [InlineData("v3-2026-11-29-e64073c-failed.json", 15, 228, true)]
    public void StopPointInPlan_LogOfEachVersion_TheFirstUnfinishedBurnRunInTheRowItLogged(string fixture, int row, long moveIndex, bool sameIndex)
    {
        var record = RunLogStore.Read(Path.Combine(FixtureFolder, fixture));
        var job = PreparedJob.Prepare(RunReplay.ToJobSpec(record with { Image = record.Image with { Path = TestRuns.Asset("qr-code.bmp") } }));

        var stop = RunReplay.StopPointInPlan(record, () => job.Plan)!;

        // The old planner numbered the moves otherwise; the row it logged agrees with today's plan either way.
        Assert.Equal(row, stop.Row);
        Assert.Equal(sameIndex, stop.MoveIndex == moveIndex);
        var burnsBefore = job.Plan.Moves().Take((int)stop.MoveIndex).Count(m => m.Kind == MoveKind.Burn);
        Assert.Equal(record.RunsDone, burnsBefore);
    }

    private static MachineProfile MachineProfileFromFile(string json)
    {
        var path = Path.Combine(Path.GetTempPath(), $"le-profile-{Guid.NewGuid():N}.json");
        File.WriteAllText(path, json);
        try
        {
            return MachineProfile.Load(path);
        }
        finally
        {
            File.Delete(path);
        }
    }
}
