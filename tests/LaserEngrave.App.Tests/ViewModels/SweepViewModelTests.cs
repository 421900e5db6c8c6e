using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Sweeps;
using LaserEngrave.Simulator;
using NSubstitute;

namespace LaserEngrave.App.Tests.ViewModels;

/// <summary>The app's sweep: planned live from the job's process and origin, run on the in-process simulator in virtual time, logged.</summary>
public sealed class SweepViewModelTests : IDisposable
{
    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private readonly MachineViewModel _machine;
    private readonly JobViewModel _job;
    private readonly SweepViewModel _sweep;

    public SweepViewModelTests()
    {
        var activity = new MachineActivity();
        _machine = new MachineViewModel(new MachineConnectionFactory(new SimulatorOptions()), MachineProfile.Default, activity);
        _job = new JobViewModel(new ImageService(), MachineProfile.Default, activity);
        var store = Substitute.For<IRunLogStore>();
        store.Folder.Returns(_folder.Path);
        _sweep = new SweepViewModel(_job, _machine, store, TimeProvider.System);
    }

    [Fact]
    public void Plan_JobProcessAndOrigin_CellsTakeThemAndVaryTheRest()
    {
        _job.OriginXMm = 7;
        _job.OriginYMm = 8;
        _job.LaserFrequencyHz = 2000;

        _sweep.Labels = false;
        _sweep.Columns = string.Empty;
        _sweep.Rows = "speed=0.5,1";

        var plan = Assert.IsType<SweepPlan>(_sweep.Plan);
        Assert.Equal(2, plan.Cells.Count);
        Assert.Equal((7.0, 8.0), (plan.Cells[0].OriginXMm, plan.Cells[0].OriginYMm));
        Assert.Equal((1.0, 2000.0), (plan.Cells[1].Job.Spec.Process.BurnSpeedMmPerS, plan.Cells[1].Job.Spec.Process.LaserFrequencyHz));
        Assert.Contains("2 × 1 cells", _sweep.Summary, StringComparison.Ordinal);
    }

    [Fact]
    public void Plan_CellsThisComputerCannotHoldOnAFrequencyOnlyGate_NamedAndNothingToRun()
    {
        // Issue 34: the grid's fast rows named before Run, not when the run reaches them 25 minutes in.
        var activity = new MachineActivity();
        var job = new JobViewModel(new ImageService(), JobViewModelTests.FrequencyOnly, activity);
        var store = Substitute.For<IRunLogStore>();
        store.Folder.Returns(_folder.Path);
        var sweep = new SweepViewModel(job, _machine, store, TimeProvider.System)
        {
            Labels = false,
            Columns = "frequency=500,1000",
        };

        sweep.Rows = "speed=1,2,3.5";

        Assert.Null(sweep.Plan);
        Assert.False(sweep.CanRun);
        Assert.Contains("(speed 3.5 mm/s, frequency 500 Hz)", sweep.Error, StringComparison.Ordinal);
        Assert.Contains("the fastest it holds is 3 mm/s", sweep.Error, StringComparison.Ordinal);

        sweep.Rows = "speed=1,2,3";
        Assert.NotNull(sweep.Plan);
    }

    [Fact]
    public void ShowOnStage_PlannedSweep_ShownUntilItsValuesAreRefused()
    {
        Assert.False(_sweep.ShowsOnStage);
        var changed = new List<string?>();
        _sweep.PropertyChanged += (_, e) => changed.Add(e.PropertyName);

        _sweep.ShowOnStage = true;
        Assert.True(_sweep.ShowsOnStage);

        _sweep.Rows = "speed=1,99";
        Assert.False(_sweep.ShowsOnStage);
        Assert.True(changed.Count(n => n == nameof(SweepViewModel.ShowsOnStage)) >= 2, string.Join(", ", changed));
    }

    [Fact]
    public void Plan_BadRows_ErrorAndNoRun()
    {
        _sweep.Rows = "speed=1,99";

        Assert.Null(_sweep.Plan);
        Assert.Contains("speed 99 mm/s: outside what the stage takes", _sweep.Error, StringComparison.Ordinal);
        Assert.False(_sweep.RunSweepCommand.CanExecute(null));
    }

    [Fact(Timeout = 120_000)]
    public async Task RunSweep_OnTheSimulator_EveryCellCompletedAndTheLogWritten()
    {
        _job.OriginXMm = 5;
        _job.OriginYMm = 5;
        _sweep.CellMm = 0.3;
        _sweep.SpacingMm = 0.2;
        _sweep.Rows = "speed=1,2";
        _sweep.Columns = "frequency=500,1000";
        await _machine.ConnectCommand.ExecuteAsync(null);
        Assert.True(_sweep.RunSweepCommand.CanExecute(null), _sweep.Error ?? _machine.Error);
        var texts = new List<string>();
        var fractions = new List<double>();
        var positions = new HashSet<long?>();
        var paced = new HashSet<(long X, long Y)>();
        _sweep.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(SweepViewModel.Progress) && _sweep.ProgressText is { } text)
            {
                texts.Add(text);
                fractions.Add(_sweep.Fraction);
                positions.Add(_machine.XMicrosteps);
            }
            else if (e.PropertyName == nameof(SweepViewModel.Status) && _sweep.Status is { } status)
            {
                texts.Add(status);
            }
            else if (e.PropertyName == nameof(SweepViewModel.LaserMicrosteps) && _sweep.LaserMicrosteps is { } laser)
            {
                paced.Add(laser);
            }
        };

        await _sweep.RunSweepCommand.ExecuteAsync(null);

        // Counted as the grid counts them: the labels apart, then 4 cells (not "2 of 5 done" for a 2 x 2 grid).
        Assert.Contains(texts, t => t.StartsWith("the labels, then 4 cells", StringComparison.Ordinal));
        Assert.Contains(texts, t => t.StartsWith("cell 1 of 4: row 1, column 1 (speed 1 mm/s, frequency 500 Hz)", StringComparison.Ordinal));
        Assert.Contains(texts, t => t.StartsWith("cell 4 of 4: row 2, column 2 (speed 2 mm/s, frequency 1000 Hz)", StringComparison.Ordinal));
        Assert.Contains(texts, t => t.StartsWith("3 of 4 cells done", StringComparison.Ordinal));
        Assert.DoesNotContain(texts, t => t.Contains("of 5", StringComparison.Ordinal));
        Assert.Equal(fractions.Order(), fractions);
        Assert.True(positions.Count > 4, "the laser's cross moves with the sweep");
        Assert.True(paced.Count > 4, "the cross is drawn at the sweep's pace, from its cells' plans");
        Assert.Null(_sweep.LaserMicrosteps);
        Assert.Equal((true, true), (_machine.XHomed, _machine.YHomed));
        var record = Assert.IsType<Core.Logging.SweepRecord>(_sweep.LastSweep);
        Assert.Equal(RunOutcome.Completed, record.Outcome);
        Assert.All(record.Cells, c => Assert.Equal(RunOutcome.Completed, c.Run!.Outcome));

        // 50 µm pixels at 2 mm/s and 500 Hz: 12.5 pulses each.
        var cell = record.Cells.Single(c => c.Parameters["speedMmPerS"] == 2 && c.Parameters["frequencyHz"] == 500);
        Assert.InRange(cell.Run!.Simulation!.PulsesPerPixel.Mean, 11.5, 13.5);
        Assert.Single(Directory.GetFiles(_folder.Path, "*.sweep.json"));
        Assert.StartsWith("completed: 4 of 4 cells", _sweep.Status, StringComparison.Ordinal);
        Assert.False(_sweep.IsRunning);
    }

    [Fact]
    public void Plan_BadCellAndRows_ThePanelsFieldNamesNotTheCommandLines()
    {
        _sweep.CellMm = 0;
        Assert.StartsWith("Cell 0: must be above 0", _sweep.Error, StringComparison.Ordinal);

        _sweep.CellMm = 1;
        _sweep.Rows = "speed";
        Assert.StartsWith("Rows speed: expected PARAMETER=", _sweep.Error, StringComparison.Ordinal);
        Assert.DoesNotContain("--", _sweep.Error, StringComparison.Ordinal);
    }

    private static readonly MachineProfile ThreeAxis = MachineProfile.Default with { Z = new ZAxisProfile { FocusMm = 12.5, MinMm = 5, MaxMm = 20 } };

    [Fact]
    public void Focus_TwoAxisMachine_RefusedAndNotOffered()
    {
        _sweep.Rows = "focus=-100,0,100";

        Assert.Null(_sweep.Plan);
        Assert.Contains("the machine has no Z axis", _sweep.Error, StringComparison.Ordinal);
        Assert.False(_sweep.FocusAvailable);
        Assert.DoesNotContain("focus", _sweep.ParameterNames, StringComparison.Ordinal);
        Assert.Contains("no Z axis", _sweep.FocusNote, StringComparison.Ordinal);
        Assert.False(_sweep.FocalSeriesCommand.CanExecute(null));
    }

    [Fact]
    public void FocalSeries_ProfileWithZ_NineCellsFromMinus200To200()
    {
        _job.UseProfile(ThreeAxis);

        _sweep.FocalSeriesCommand.Execute(null);

        Assert.True(_sweep.FocusAvailable);
        Assert.Contains("focus", _sweep.ParameterNames, StringComparison.Ordinal);
        var plan = Assert.IsType<SweepPlan>(_sweep.Plan);
        Assert.Equal([-200.0, -150, -100, -50, 0, 50, 100, 150, 200], plan.Cells.Select(c => c.Parameters["focusUm"]));
        Assert.Equal(ThreeAxis.Z!.MicrostepsAt(-200), plan.Cells[0].FocusZMicrosteps);
        Assert.Equal(SweepPattern.Lines, _sweep.Pattern);
    }

    [Fact]
    public void Pattern_ImageWithoutAnImage_AskedToLoadOne()
    {
        _sweep.Pattern = SweepPattern.Image;

        Assert.Null(_sweep.Plan);
        Assert.False(_sweep.ImageAvailable);
        Assert.Contains("load an image first", _sweep.Error, StringComparison.Ordinal);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunSweep_FocusOnTheSimulatorWithZ_EachCellBurnedAtItsFocus()
    {
        var activity = new MachineActivity();
        var machine = new MachineViewModel(new MachineConnectionFactory(new SimulatorOptions()), ThreeAxis, activity);
        var job = new JobViewModel(new ImageService(), ThreeAxis, activity) { OriginXMm = 5, OriginYMm = 5 };
        var store = Substitute.For<IRunLogStore>();
        store.Folder.Returns(_folder.Path);
        var sweep = new SweepViewModel(job, machine, store, TimeProvider.System) { CellMm = 0.2, SpacingMm = 0.2, Labels = false, Columns = string.Empty, Rows = "focus=-100,100" };
        await machine.ConnectCommand.ExecuteAsync(null);
        Assert.True(sweep.RunSweepCommand.CanExecute(null), sweep.Error ?? machine.Error);

        await sweep.RunSweepCommand.ExecuteAsync(null);

        var record = Assert.IsType<Core.Logging.SweepRecord>(sweep.LastSweep);
        Assert.Equal(RunOutcome.Completed, record.Outcome);
        foreach (var cell in record.Cells)
        {
            var expected = ThreeAxis.Z!.MicrostepsAt(cell.Parameters["focusUm"]);
            Assert.Equal(expected, cell.ZReachedMicrosteps);
            Assert.Equal((expected, 0), (cell.Run!.Simulation!.Focus!.ZMinMicrosteps, cell.Run.Simulation.Focus.LaserOnWhileZMoving));
        }

        await machine.DisconnectCommand.ExecuteAsync(null);
    }

    public void Dispose() => _folder.Dispose();
}
