using LaserEngrave.Cli.Commands;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Cli.Tests;

public class ProgressPrinterTests
{
    private static RunProgress At(double percent, RunState state = RunState.Running, long runsDone = 50) =>
        new(state, 10, 40, runsDone, 200, percent, TimeSpan.FromSeconds(30), TimeSpan.FromSeconds(95), 0, 0, false);

    [Fact]
    public void Bar_Running_ShowsFilledShareRowsPercentAndEta()
    {
        Assert.Equal("[########......................]  25.0 %  row 10/40  ETA 1 min 35.0 s   ", ProgressPrinter.Bar(At(25)));
    }

    [Theory]
    [InlineData(false)]
    [InlineData(true)]
    public void Report_TerminalHungUp_WritesFailQuietlySoTheAbortGoesOn(bool terminal)
    {
        using var output = new HungUpWriter();
        var printer = new ProgressPrinter(output, terminal);

        printer.Report(At(10));
        printer.Report(At(20, RunState.Aborting));
        printer.Finish();

        Assert.True(output.Attempts >= 2);
    }

    /// <summary>A terminal that has hung up: every write fails with EIO.</summary>
    private sealed class HungUpWriter : StringWriter
    {
        public int Attempts { get; private set; }

        public override void Write(string? value) => throw Fail();

        public override void WriteLine(string? value) => throw Fail();

        public override void WriteLine() => throw Fail();

        private IOException Fail()
        {
            Attempts++;
            return new IOException("Input/output error");
        }
    }

    [Fact]
    public void Report_SessionOfTwoPasses_BarAndLinesSayWhichPass()
    {
        using var output = new StringWriter();
        var printer = new ProgressPrinter(output, terminal: false);

        printer.Report(new EngraveProgress(RunState.Preflight, 2, 2, 0, 100, false, At(0, RunState.Preflight)));
        printer.Report(new EngraveProgress(RunState.Running, 2, 2, 10, 100, false, At(10)));

        Assert.Equal(
            ["preflight: checking the machine and the job (pass 2 of 2)", "running: 10 %, row 10 of 40, 50 of 200 burn runs, pass 2 of 2, 1 min 35.0 s left"],
            output.ToString().TrimEnd().Split(Environment.NewLine));
        Assert.Contains("row 10/40  pass 1 of 2  ETA", ProgressPrinter.Bar(At(25), "1 of 2"), StringComparison.Ordinal);
    }

    [Fact]
    public void Report_SessionRecovering_SaysOnceThatTheRunIsRecoveringAndFromWhichRow()
    {
        using var output = new StringWriter();
        var printer = new ProgressPrinter(output, terminal: false);

        printer.Report(new EngraveProgress(RunState.Preflight, 1, 2, 0, 100, false, At(0, RunState.Preflight)));
        printer.Report(new EngraveProgress(RunState.Running, 1, 2, 10, 100, false, At(10)));
        // The session goes on after a timing doubt: the same pass's preflight again, reported more than once, then running.
        printer.Report(new EngraveProgress(RunState.Preflight, 1, 2, 10, 100, false, At(0, RunState.Preflight) with { RowsDone = 0 }, Recoveries: 1, Recovering: true));
        printer.Report(new EngraveProgress(RunState.Preflight, 1, 2, 10, 100, false, At(0, RunState.Preflight) with { RowsDone = 0 }, Recoveries: 1, Recovering: true));
        printer.Report(new EngraveProgress(RunState.Running, 1, 2, 10, 100, false, At(10), Recoveries: 1));
        // The next pass's preflight is a new start, said as the first one.
        printer.Report(new EngraveProgress(RunState.Preflight, 2, 2, 0, 100, false, At(0, RunState.Preflight), Recoveries: 1));

        Assert.Equal(
            [
                "preflight: checking the machine and the job (pass 1 of 2)",
                "running: 10 %, row 10 of 40, 50 of 200 burn runs, pass 1 of 2, 1 min 35.0 s left",
                "recovering: the run fell behind its timing, laser off; checking the machine again, then going on from row 11 of 40, pass 1 of 2",
                "running: 10 %, row 10 of 40, 50 of 200 burn runs, pass 1 of 2, 1 min 35.0 s left",
                "preflight: checking the machine and the job (pass 2 of 2)",
            ],
            output.ToString().TrimEnd().Split(Environment.NewLine));
    }

    [Fact]
    public void Report_HundredRecoveries_SaysThreeThenCountsTheRestOnceAtTheEnd()
    {
        // Issue 31 finding 6: a run that went on after every row printed two lines each time.
        using var output = new StringWriter();
        var printer = new ProgressPrinter(output, terminal: false);

        printer.Report(new EngraveProgress(RunState.Running, 1, 1, 10, 100, false, At(10)));
        for (var n = 1; n <= 100; n++)
        {
            printer.Report(new EngraveProgress(RunState.Preflight, 1, 1, 10, 100, false, At(0, RunState.Preflight) with { RowsDone = 0 }, Recoveries: n, Recovering: true));
            printer.Report(new EngraveProgress(RunState.Running, 1, 1, 10, 100, false, At(10), Recoveries: n));
        }

        printer.Finish();

        var lines = output.ToString().TrimEnd().Split(Environment.NewLine);
        Assert.Equal(3, lines.Count(l => l.StartsWith("recovering: the run fell behind", StringComparison.Ordinal)));
        Assert.Equal(4, lines.Count(l => l.StartsWith("running:", StringComparison.Ordinal)));
        Assert.Equal("recovering: went on after 97 more timing doubts (100 in all; the run log lists each)", lines[^1]);
    }

    // The next layer's first pass has the pass number of the one before: only the session knows a recovery from a new start.
    [Fact]
    public void Report_NextLayersFirstPass_IsANewStartNotARecovery()
    {
        using var output = new StringWriter();
        var printer = new ProgressPrinter(output, terminal: false);

        printer.Report(new EngraveProgress(RunState.Running, 1, 1, 10, 100, false, At(10)));
        printer.Report(new EngraveProgress(RunState.Preflight, 1, 1, 0, 100, false, At(0, RunState.Preflight), Layer: 2));

        Assert.Equal(
            ["running: 10 %, row 10 of 40, 50 of 200 burn runs, 1 min 35.0 s left", "preflight: checking the machine and the job"],
            output.ToString().TrimEnd().Split(Environment.NewLine));
    }

    [Fact]
    public void Report_TerminalRecovering_EndsTheBarsLineAndSaysItOnItsOwnLine()
    {
        using var output = new StringWriter();
        var printer = new ProgressPrinter(output, terminal: true);

        printer.Report(new EngraveProgress(RunState.Running, 1, 1, 10, 100, false, At(25)));
        printer.Report(new EngraveProgress(RunState.Preflight, 1, 1, 10, 100, false, At(0, RunState.Preflight), Recoveries: 1, Recovering: true));
        printer.Report(new EngraveProgress(RunState.Running, 1, 1, 10, 100, false, At(25), Recoveries: 1));
        printer.Finish();

        Assert.Equal(
            "\r" + ProgressPrinter.Bar(At(25)) + Environment.NewLine
            + "recovering: the run fell behind its timing, laser off; checking the machine again, then going on from row 11 of 40" + Environment.NewLine
            + "\r" + ProgressPrinter.Bar(At(25)) + Environment.NewLine,
            output.ToString());
    }

    [Fact]
    public void Report_JobOfLayers_LinesNameTheLayerAndCountADrawingsStrokes()
    {
        using var output = new StringWriter();
        // The plate's first two layers: "marks", a drawing, then "logo", an image.
        var plate = Core.Jobs.JobFile.Load(Path.Combine(CliHarness.RepositoryRoot, "assets", "jobs", "plate.json"));
        var printer = new ProgressPrinter(output, terminal: false) { Job = Core.Jobs.LayeredJob.Prepare([.. plate.Take(2)], Core.Geometry.MachineProfile.Default) };

        // Two one-pass layers: each is pass 1 of 1 (the session's passes summed over the layers are not the layer's).
        printer.Report(new EngraveProgress(RunState.Running, 1, 2, 10, 100, false, At(10), Layer: 1, LayerPass: 1, LayerPasses: 1));
        printer.Report(new EngraveProgress(RunState.Running, 2, 2, 10, 100, false, At(20), Layer: 2, LayerPass: 1, LayerPasses: 1));

        Assert.Equal(
            [
                "running: 10 %, stroke 10 of 40, 50 of 200 paths, pass 1 of 1, layer 1 of 2 \"marks\", 1 min 35.0 s left",
                "running: 20 %, row 10 of 40, 50 of 200 burn runs, pass 1 of 1, layer 2 of 2 \"logo\", 1 min 35.0 s left",
            ],
            output.ToString().TrimEnd().Split(Environment.NewLine));
    }

    [Fact]
    public void Report_SessionsPassCompleted_ShownAsTheSessionsStateNotDone()
    {
        using var output = new StringWriter();
        var printer = new ProgressPrinter(output, terminal: false);

        printer.Report(new EngraveProgress(RunState.Running, 1, 2, 100, 100, false, At(100, RunState.Completed, 200)));

        Assert.StartsWith("running: 100 %", output.ToString(), StringComparison.Ordinal);
    }

    [Fact]
    public void Report_Redirected_OneLinePerTenPercentAndPerStateChange()
    {
        using var output = new StringWriter();
        var printer = new ProgressPrinter(output, terminal: false);

        foreach (var percent in new[] { 0.0, 1, 5, 9.9, 10, 11, 19, 25, 26 })
        {
            printer.Report(At(percent));
        }

        printer.Report(At(26, RunState.Pausing));

        Assert.Equal(
            ["running: 0 %", "running: 10 %", "running: 25 %", "pausing: 26 %"],
            output.ToString().TrimEnd().Split('\n').Select(line => line[..line.IndexOf(',', StringComparison.Ordinal)]));
    }

    [Fact]
    public void Report_Terminal_RedrawsOneLineWithCarriageReturnAndFinishEndsIt()
    {
        using var output = new StringWriter();
        var printer = new ProgressPrinter(output, terminal: true);

        printer.Report(At(50));
        printer.Finish();

        Assert.Equal("\r" + ProgressPrinter.Bar(At(50)) + Environment.NewLine, output.ToString());
    }

    [Theory]
    [InlineData(RunState.Completed, 200, "done")]
    [InlineData(RunState.Completed, 50, "stopped")]
    [InlineData(RunState.Aborted, 50, "stopped")]
    [InlineData(RunState.Failed, 50, "stopped")]
    [InlineData(RunState.Paused, 50, "paused")]
    public void StateLabel_EndedRun_SaysDoneOnlyWhenEveryRunWasBurned(RunState state, long runsDone, string expected)
    {
        Assert.Equal(expected, ProgressPrinter.StateLabel(At(50, state, runsDone)));
    }
}
