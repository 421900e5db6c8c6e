using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Logging;

public sealed class RunSummaryTextTests : IDisposable
{
    private readonly TestRuns runs = new();

    [Fact]
    public void Format_FailedRun_SaysWhatFailedWhereAndTheParameters()
    {
        var record = runs.FailedRecord();

        var text = RunSummaryText.Format(record);

        Assert.Contains("Outcome:            FAILED", text, StringComparison.Ordinal);
        Assert.Contains("Fault:              x axis: no reply within 500 ms (timeout)", text, StringComparison.Ordinal);
        Assert.Contains("Laser off:          confirmed by the gate", text, StringComparison.Ordinal);
        // Issue 23: the stop is counted in the rows done, as the run bar and the "Done" line count; the image row follows.
        // Issue 31, finding 8: the stop in mm, as the app shows the stage, not in microsteps only.
        Assert.Contains($"Stopped at:         after 11 of {record.RowsTotal} rows, move 40 (image row 12), stage at X 12.249 mm, Y 9.799 mm (123456, 98765 microsteps)", text, StringComparison.Ordinal);
        Assert.Contains($"Done:               11 of {record.RowsTotal} rows", text, StringComparison.Ordinal);
        Assert.Contains("Started:            2026-11-23 14:30:05 +02:00", text, StringComparison.Ordinal);
        Assert.Contains(record.Image.Sha256, text, StringComparison.Ordinal);
        Assert.Contains("burn 0.8 mm/s, travel 3 mm/s, acceleration 40 mm/s²", text, StringComparison.Ordinal);
        Assert.Contains("Laser frequency:    1500 Hz", text, StringComparison.Ordinal);
        Assert.Contains("optimized, unidirectional, overscan 0.2 mm", text, StringComparison.Ordinal);
        Assert.Contains("Duration:           1 min 01.5 s, estimated 1 min 10.3 s (on the simulator's clock); engraving 0 min 55.5 s, estimated 0 min 54.8 s", text, StringComparison.Ordinal);
        Assert.Contains("firmware 5.29", text, StringComparison.Ordinal);
        Assert.Contains("Repeats:            /logs/2026-11-22_090000_S-16.json", text, StringComparison.Ordinal);
        Assert.Contains("Notes:              first try\n                    focus 2 turns down", text, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData(true, LaserOffPath.Off, "Laser off:          confirmed by the gate (it acknowledged OFF)")]
    [InlineData(true, LaserOffPath.OffAgain, "Laser off:          confirmed by the gate acknowledging OFF, late or sent again (it had refused or not answered a switch-off in time")]
    [InlineData(true, LaserOffPath.FrequencyZero, "Laser off:          confirmed by the gate acknowledging FREQ 0")]
    [InlineData(false, LaserOffPath.None, "Laser off:          NOT CONFIRMED: the gate acknowledged neither OFF nor FREQ 0; its port was closed so that its watchdog switches the laser off; a person must check the laser")]
    public void Format_LaserOffPath_SaysWhichCommandConfirmedItOrThatNoneDid(bool confirmed, LaserOffPath path, string line)
    {
        var record = runs.FailedRecord() with { Fault = new RunFault("laser gate refused 'OFF': ERR 1", null, confirmed, path) };

        var text = RunSummaryText.Format(record);
        var read = RunRecordJson.Deserialize(RunRecordJson.Serialize(record), "test.json");

        Assert.Contains(line, text, StringComparison.Ordinal);
        Assert.Equal(path, read.Fault!.LaserOffBy);
    }

    [Fact]
    public void Format_StopPointNamingACutPixelAndTheCutIfTheWatchdogDidNotTrip_SaysBoth()
    {
        var stop = new RunStopPoint(5, 31, 117268, 107548)
        {
            CutPixel = new PixelIndex(13, 5),
            OffByGateWatchdog = true,
            OffResumeXMicrosteps = 117000,
            OffCutPixel = new PixelIndex(12, 5),
        };
        var record = runs.FailedRecord() with { StoppedAt = stop };

        var text = RunSummaryText.Format(record);
        var read = RunRecordJson.Deserialize(RunRecordJson.Serialize(record), "test.json");

        Assert.Contains("Resumes:            from the run's start; its pixels up to column 13, row 5 (where the laser went off at the latest, or its switch-on was never acknowledged) may get part of their dose twice", text, StringComparison.Ordinal);
        Assert.Contains("Or resumes:         mid-run at X 117000 microsteps if the gate reports its watchdog did not trip (it heard the OFF); then pixel column 12, row 5 burns twice", text, StringComparison.Ordinal);
        Assert.Equal(stop, read.StoppedAt);
    }

    [Fact]
    public void Format_CompletedRun_HasNoFaultOrStopLines()
    {
        var record = runs.FailedRecord() with { Outcome = RunOutcome.Completed, Fault = null, StoppedAt = null, Notes = null };

        var text = RunSummaryText.Format(record);

        Assert.Contains("Outcome:            completed", text, StringComparison.Ordinal);
        Assert.DoesNotContain("Fault:", text, StringComparison.Ordinal);
        Assert.DoesNotContain("Stopped at:", text, StringComparison.Ordinal);
        Assert.Contains("Notes:              (none)", text, StringComparison.Ordinal);
    }

    [Fact]
    public void Format_TwoPassesOneDone_SaysSo()
    {
        var record = runs.FailedRecord() with { Passes = 2, PassesDone = 1 };

        var text = RunSummaryText.Format(record);

        Assert.Contains("Passes:             1 of 2 done", text, StringComparison.Ordinal);
    }

    [Fact]
    public void Format_TwoLayersOfOnePass_CountsLayersNotPassesAndSaysWhoseImage()
    {
        RunLayer Layer(string name, string source) => new(name, source, "0", LayerMode.Raster, null, 1, 1, 0, 0, 1, 1000, 1) { PassesDone = 1, Outcome = RunOutcome.Completed };
        var record = runs.FailedRecord() with { Passes = 2, PassesDone = 2, Layers = [Layer("logo", "/jobs/logo.png"), Layer("id", "/jobs/id.png")] };

        var text = RunSummaryText.Format(record);

        Assert.DoesNotContain("Passes:", text, StringComparison.Ordinal);
        Assert.Contains("Layers:             2 of 2 completed (each with its passes below)", text, StringComparison.Ordinal);
        Assert.Contains("Image (layer 1):", text, StringComparison.Ordinal);
        Assert.Contains("\"id\" raster id.png", text, StringComparison.Ordinal);
    }

    [Fact]
    public void Format_SinglePass_HasNoPassesLine()
    {
        var text = RunSummaryText.Format(runs.FailedRecord());

        Assert.DoesNotContain("Passes:", text, StringComparison.Ordinal);
    }

    [Fact]
    public void Format_LateSwitchesAndRecoveries_CountsThemInOneLineAndTheTimingSaysBoth()
    {
        // Issue 22 item 3: late switches are counted and logged, in the summary as in the app's last run.
        var record = runs.FailedRecord() with
        {
            LateSwitches = new LateSwitches(4, 1.4213, 1.5, 1),
            Recoveries = [new RunRecovery(1, "x axis: switch-on 2.1 µm late", 40, 12), new RunRecovery(1, "x axis: reply late", 90, 20)],
        };

        var text = RunSummaryText.Format(record);

        Assert.Contains("Late switches:      switch-ons: 4 within the 1.5 µm edge tolerance (latest 1.42 µm); switch-offs: 1 (the burst had ended the run by itself)\n", text, StringComparison.Ordinal);
        Assert.Contains("Went on after:      pass 1, row 13 (move 40)", text, StringComparison.Ordinal);

        // Issue 36 finding 11: "the laser stayed off for that run" beside "284 of 284 burn runs": said once how both hold.
        Assert.Contains("Went on:            each run the laser was kept off for at a doubt was burned when the job went on from there", text, StringComparison.Ordinal);
        Assert.Equal(
            "late switch-ons: 4 within the 1.5 µm edge tolerance (latest 1.42 µm); switch-offs: 1 (the burst had ended the run by itself); went on after 2 timing doubts",
            RunSummaryText.Timing(record));
    }

    [Fact]
    public void Format_HundredsOfRecoveries_ListsThreeAndCountsTheRestInOneLine()
    {
        // Issue 31 finding 6: 100 passes gave 2,284 lines of "Went on after", burying the run's end.
        var recoveries = Enumerable.Range(0, 500).Select(i => new RunRecovery(1 + (i / 5), "x axis: reply late", 40 + i, i % 33)).ToList();
        var record = runs.FailedRecord() with { Recoveries = recoveries };

        var lines = RunSummaryText.Format(record).Split('\n').Where(l => l.StartsWith("Went on after:", StringComparison.Ordinal)).ToList();

        Assert.Equal(4, lines.Count);
        Assert.Equal("Went on after:      pass 1, row 1 (move 40): x axis: reply late", lines[0]);
        Assert.Equal("Went on after:      497 more timing doubts (passes 1-100), listed in the JSON record's recoveries", lines[3]);
        Assert.Equal(500, RunRecordJson.Deserialize(RunRecordJson.Serialize(record), "run.json").Recoveries!.Count);
    }

    [Fact]
    public void Format_GuardsWidened_SaysTheScaleInTheSummaryTheTimingAndTheJson()
    {
        // Issue 34: lines shrank under load (guards widened up to 8x) and neither the log nor the summary said so.
        var record = runs.FailedRecord() with { GuardScale = 2.4, LateSwitches = null, Recoveries = [] };

        Assert.Contains("Guards:             guards 2.4 x the profile's latency spread", RunSummaryText.Format(record), StringComparison.Ordinal);
        Assert.StartsWith("guards 2.4 x the profile's latency spread", RunSummaryText.Timing(record), StringComparison.Ordinal);
        Assert.Equal(2.4, RunRecordJson.Deserialize(RunRecordJson.Serialize(record), "run.json").GuardScale);
    }

    [Fact]
    public void Format_NoLateSwitches_HasNoLineAndNoTiming()
    {
        var record = runs.FailedRecord() with { LateSwitches = new LateSwitches(0, 0, 1.5), Recoveries = [] };

        Assert.DoesNotContain("Late switches:", RunSummaryText.Format(record), StringComparison.Ordinal);
        Assert.Null(RunSummaryText.Timing(record));
    }

    [Theory]
    [InlineData(61.5, "1 min 01.5 s")]
    [InlineData(3723, "1 h 02 min 03 s")]
    [InlineData(double.NaN, "unknown")]
    public void Duration_Seconds_ReadsAsMinutesOrHours(double seconds, string expected)
    {
        Assert.Equal(expected, RunSummaryText.Duration(seconds));
    }

    public void Dispose() => runs.Dispose();

    [Fact]
    public void Format_LineWarnings_ListsTheFirstThreeAndCountsTheRestAndTheJsonKeepsThem()
    {
        var record = runs.FailedRecord() with { LineWarnings = ["a", "b", "c", "d", "e"] };

        var text = RunSummaryText.Format(record);
        var read = RunRecordJson.Deserialize(RunRecordJson.Serialize(record), "test.json");

        Assert.Contains("Line:               a\n", text, StringComparison.Ordinal);
        Assert.Contains("Line:               c\n", text, StringComparison.Ordinal);
        Assert.DoesNotContain("Line:               d\n", text, StringComparison.Ordinal);
        Assert.Contains("Line:               2 more, listed in the JSON record's lineWarnings\n", text, StringComparison.Ordinal);
        Assert.Equal(["a", "b", "c", "d", "e"], read.LineWarnings);
    }
}
