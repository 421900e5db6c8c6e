using System.Globalization;
using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.App.ViewModels;

/// <summary>The Test moves view: jog, go to, go to the job's origin, trace its frame, fire a test burst, home.</summary>
/// <remarks>Every move runs with the laser off; none is allowed while a run is under way.</remarks>
public sealed partial class TestMovesViewModel : ObservableObject
{
    /// <summary>The jog step sizes offered, µm: 1 µm to 10 mm.</summary>
    public static IReadOnlyList<double> StepChoicesUm { get; } = [1, 10, 100, 1000, 10000];

    private readonly MachineViewModel _machine;
    private readonly JobViewModel _job;

    public TestMovesViewModel(MachineViewModel machine, JobViewModel job)
    {
        ArgumentNullException.ThrowIfNull(machine);
        ArgumentNullException.ThrowIfNull(job);
        _machine = machine;
        _job = job;
    }

    [ObservableProperty]
    public partial double StepUm { get; set; } = 100;

    [ObservableProperty]
    public partial double GoToXMm { get; set; }

    [ObservableProperty]
    public partial double GoToYMm { get; set; }

    [ObservableProperty]
    public partial int TestFirePulses { get; set; } = 100;

    /// <summary>Set by the run view-model while a run owns the machine.</summary>
    [ObservableProperty]
    public partial bool RunActive { get; set; }

    /// <summary>The last failure of a test move, one line.</summary>
    [ObservableProperty]
    public partial string? Error { get; private set; }

    /// <summary>Moves one axis by the step size; direction is "x+", "x-", "y+" or "y-".</summary>
    [RelayCommand(IncludeCancelCommand = true)]
    private Task JogAsync(string direction, CancellationToken cancellationToken) => Move(async (connection, ct) =>
    {
        var (axis, sign) = direction switch
        {
            "x+" => (connection.Stage.X, 1),
            "x-" => (connection.Stage.X, -1),
            "y+" => (connection.Stage.Y, 1),
            "y-" => (connection.Stage.Y, -1),
            _ => throw new ArgumentException($"jog direction '{direction}' is not one of x+, x-, y+, y-"),
        };
        if (!(StepUm > 0) || StepUm > 60000)
        {
            throw new ArgumentException($"step {N(StepUm)} µm must be above 0 and at most 60000 µm");
        }

        var current = await axis.GetPositionAsync(ct).ConfigureAwait(false);
        var target = current + (sign * JobGeometry.Round(StageUnits.UmToMicrosteps(StepUm, _machine.Profile.X.MicrostepUm)));
        var travel = axis == connection.Stage.X ? _machine.Profile.X.TravelMicrosteps : _machine.Profile.Y.TravelMicrosteps;
        await axis.MoveAbsoluteAsync(Math.Clamp(target, 0, travel), ct).ConfigureAwait(false);
    }, cancellationToken);

    [RelayCommand(IncludeCancelCommand = true)]
    private Task GoToAsync(CancellationToken cancellationToken) => Move(
        (connection, ct) => MoveBothAsync(connection.Stage, Microsteps(GoToXMm, _machine.Profile.X), Microsteps(GoToYMm, _machine.Profile.Y), ct),
        cancellationToken);

    /// <summary>Moves to the job's top-left corner, where the first pixel edge lies.</summary>
    [RelayCommand(IncludeCancelCommand = true)]
    private Task GoToOriginAsync(CancellationToken cancellationToken) => Move(async (connection, ct) =>
    {
        var geometry = RequireJob().Geometry.Geometry;
        await MoveBothAsync(connection.Stage, geometry.EdgeX(0), geometry.EdgeY(0), ct).ConfigureAwait(false);
    }, cancellationToken);

    /// <summary>Traces the job's outline with the laser off, so the user sees where it will land.</summary>
    [RelayCommand(IncludeCancelCommand = true)]
    private Task FrameAsync(CancellationToken cancellationToken) => Move(async (connection, ct) =>
    {
        var job = RequireJob();
        if (!job.Geometry.FitsTravel)
        {
            throw new ArgumentException("the job lies outside the stage's travel: move the origin or make it smaller");
        }

        var g = job.Geometry.Geometry;
        long left = g.EdgeX(0), right = g.EdgeX(g.WidthPx), top = g.EdgeY(0), bottom = g.EdgeY(g.HeightPx);
        await MoveBothAsync(connection.Stage, left, top, ct).ConfigureAwait(false);
        await connection.Stage.X.MoveAbsoluteAsync(right, ct).ConfigureAwait(false);
        await connection.Stage.Y.MoveAbsoluteAsync(bottom, ct).ConfigureAwait(false);
        await connection.Stage.X.MoveAbsoluteAsync(left, ct).ConfigureAwait(false);
        await connection.Stage.Y.MoveAbsoluteAsync(top, ct).ConfigureAwait(false);
    }, cancellationToken);

    /// <summary>Fires a burst where the stage stands (the stage does not move), at the job's frequency.</summary>
    [RelayCommand(IncludeCancelCommand = true)]
    private Task TestFireAsync(CancellationToken cancellationToken) => Run(async (connection, ct) =>
    {
        if (TestFirePulses is < 1 or > 100000)
        {
            throw new ArgumentException($"test fire of {TestFirePulses} pulses must be 1 to 100000 pulses");
        }

        var frequency = (int)Math.Round(_job.LaserFrequencyHz, MidpointRounding.AwayFromZero);
        if (frequency < 1)
        {
            throw new ArgumentException($"laser frequency {N(_job.LaserFrequencyHz)} Hz must be at least 1 Hz");
        }

        await connection.Gate.BurstAsync(TestFirePulses, frequency, ct).ConfigureAwait(false);
        _machine.GateState = MachineViewModel.Describe(await connection.Gate.GetStateAsync(ct).ConfigureAwait(false));
    }, cancellationToken);

    private Core.Jobs.PreparedJob RequireJob() =>
        _job.Job ?? throw new ArgumentException("no job planned: open an image and give it a usable size first");

    private static long Microsteps(double mm, AxisProfile axis)
    {
        var microsteps = JobGeometry.Round(StageUnits.MmToMicrosteps(mm, axis.MicrostepUm));
        if (!double.IsFinite(mm) || microsteps < 0 || microsteps > axis.TravelMicrosteps)
        {
            throw new ArgumentException($"position {N(mm)} mm is outside the travel 0 to {N(axis.TravelMm)} mm");
        }

        return microsteps;
    }

    private static async Task MoveBothAsync(IStage stage, long x, long y, CancellationToken cancellationToken) =>
        await Task.WhenAll(stage.X.MoveAbsoluteAsync(x, cancellationToken), stage.Y.MoveAbsoluteAsync(y, cancellationToken)).ConfigureAwait(false);

    /// <summary>A move: the laser goes off first, and the positions are read afterwards.</summary>
    private Task Move(Func<Services.IMachineConnection, CancellationToken, Task> move, CancellationToken cancellationToken) => Run(async (connection, ct) =>
    {
        await connection.Gate.OffAsync(ct).ConfigureAwait(false);
        try
        {
            await move(connection, ct).ConfigureAwait(false);
        }
        finally
        {
            await _machine.ReadPositionsAsync(CancellationToken.None).ConfigureAwait(false);
        }
    }, cancellationToken);

    private async Task Run(Func<Services.IMachineConnection, CancellationToken, Task> action, CancellationToken cancellationToken)
    {
        Error = null;
        if (RunActive)
        {
            Error = "a run is under way: pause or abort it first";
            return;
        }

        await _machine.Guard(async () => await action(_machine.RequireConnection(), cancellationToken).ConfigureAwait(false)).ConfigureAwait(false);
        Error = _machine.Error;
    }

    private static string N(double value) => value.ToString("0.######", CultureInfo.InvariantCulture);
}
