using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.Core.Tests.Logging;

/// <summary>A sweep's log: written beside the runs as .sweep.json and .sweep.txt, read back whole, left out of the run list.</summary>
public sealed class SweepRecordTests : IDisposable
{
    private readonly TestRuns runs = new();

    private SweepRecord Sweep() => new()
    {
        SoftwareVersion = "test",
        StartedAt = TestRuns.Start,
        EndedAt = TestRuns.Start.AddMinutes(3),
        Outcome = RunOutcome.Failed,
        Fault = "cell row 1, column 2 (speedMmPerS 1): the stage stopped answering",
        Pattern = "square",
        CellMm = 1,
        SpacingMm = 0.5,
        OriginXMm = 5,
        OriginYMm = 6,
        Rows = "speed=0.5,1",
        Columns = "frequency=500,1000",
        SampleId = "S-9",
        Cells =
        [
            new SweepCellRecord(0, 0, new Dictionary<string, double> { ["speedMmPerS"] = 0.5, ["frequencyHz"] = 500 }, 5, 6, 1, 1, 50, 1, runs.FailedRecord() with { Outcome = RunOutcome.Completed }),
            new SweepCellRecord(0, 1, new Dictionary<string, double> { ["speedMmPerS"] = 0.5, ["frequencyHz"] = 1000 }, 6.5, 6, 1, 1, 50, 1, null),
        ],
    };

    [Fact]
    public void WriteSweep_ReadBack_EveryCellsValuesPlaceAndRun()
    {
        var store = new RunLogStore(Path.Combine(runs.Folder, "logs"));

        var files = store.WriteSweep(Sweep());
        var read = SweepRecord.Deserialize(File.ReadAllText(files.JsonPath), files.JsonPath);

        Assert.EndsWith("2026-11-23_143005_S-9.sweep.json", files.JsonPath, StringComparison.Ordinal);
        Assert.Equal(2, read.Cells.Count);
        Assert.Equal(1000, read.Cells[1].Parameters["frequencyHz"]);
        Assert.Equal((6.5, 6.0), (read.Cells[1].OriginXMm, read.Cells[1].OriginYMm));
        Assert.Equal(RunOutcome.Completed, read.Cells[0].Run!.Outcome);
        Assert.Null(read.Cells[1].Run);
        Assert.Equal("speed=0.5,1", read.Rows);
        var text = File.ReadAllText(files.TextPath);
        Assert.Contains("not run", text, StringComparison.Ordinal);
        Assert.Contains("frequencyHz 1000", text, StringComparison.Ordinal);
    }

    [Fact]
    public void List_SweepBesideARun_OnlyTheRunListed()
    {
        var store = new RunLogStore(Path.Combine(runs.Folder, "logs"));
        store.WriteSweep(Sweep());
        store.Write(runs.FailedRecord());

        var entry = Assert.Single(store.List());

        Assert.Null(entry.Error);
    }

    public void Dispose() => runs.Dispose();
}
