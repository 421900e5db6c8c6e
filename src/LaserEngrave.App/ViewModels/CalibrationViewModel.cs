using System.Globalization;
using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// The Calibration view, the command line's <c>calibrate pattern|solve|show|clear</c> as three steps: load the pattern as
/// the job (then engrave it), enter what the microscope measured and solve, store the result in the machine profile.
/// </summary>
/// <remarks>docs/calibration.md has the mathematics. The profile is the one the settings name, or a new
/// machine-profile.json in the app's data folder made from the one in use.</remarks>
public sealed partial class CalibrationViewModel : ObservableObject
{
    private readonly MainViewModel _main;
    private readonly string _dataFolder;
    private readonly TimeProvider _time;

    public CalibrationViewModel(MainViewModel main, string dataFolder, TimeProvider? time = null)
    {
        ArgumentNullException.ThrowIfNull(main);
        ArgumentException.ThrowIfNullOrWhiteSpace(dataFolder);
        _main = main;
        _dataFolder = dataFolder;
        _time = time ?? TimeProvider.System;
        _main.Job.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(JobViewModel.Profile))
            {
                OnPropertyChanged(nameof(Current));
            }
        };
    }

    /// <summary>Side of the pattern's square, mm.</summary>
    [ObservableProperty]
    public partial double SizeMm { get; set; } = 20;

    /// <summary>Pixel pitch the pattern is engraved at, µm.</summary>
    [ObservableProperty]
    public partial double PitchUm { get; set; } = 10;

    /// <summary>The pattern's distance along the X groove that was measured, mm (nominal).</summary>
    [ObservableProperty]
    public partial double XNominalMm { get; set; } = 16;

    /// <summary>What the microscope measured for it, mm; 0: not measured.</summary>
    [ObservableProperty]
    public partial double XMeasuredMm { get; set; }

    [ObservableProperty]
    public partial double YNominalMm { get; set; } = 16;

    [ObservableProperty]
    public partial double YMeasuredMm { get; set; }

    /// <summary>The measured angle between the grooves, degrees; 0: not measured.</summary>
    [ObservableProperty]
    public partial double AngleDegrees { get; set; }

    /// <summary>The square's diagonal through corner A, mm; 0: not measured.</summary>
    [ObservableProperty]
    public partial double DiagonalAcMm { get; set; }

    [ObservableProperty]
    public partial double DiagonalBdMm { get; set; }

    /// <summary>What the pattern is and what to measure on it.</summary>
    [ObservableProperty]
    public partial IReadOnlyList<string> PatternLines { get; private set; } = [];

    /// <summary>The last solution (null before one, or after a refusal).</summary>
    [ObservableProperty]
    [NotifyCanExecuteChangedFor(nameof(StoreCommand))]
    public partial CalibrationSolution? Solution { get; private set; }

    /// <summary>The solution in words: errors, uncertainty, residuals.</summary>
    [ObservableProperty]
    public partial IReadOnlyList<string> SolutionLines { get; private set; } = [];

    /// <summary>Why the last step failed, one line.</summary>
    [ObservableProperty]
    public partial string? Error { get; private set; }

    /// <summary>What the last store or clear did.</summary>
    [ObservableProperty]
    public partial string? Status { get; private set; }

    /// <summary>The calibration of the profile in use, in words.</summary>
    public string Current => _main.Job.Profile.Calibration is { } c ? c.Describe() : "not calibrated (square and true to scale assumed)";

    /// <summary>Writes the pattern into the data folder and opens it as the job at its pitch; then engrave it on a scrap sample.</summary>
    [RelayCommand]
    private void LoadPattern()
    {
        try
        {
            var pattern = CalibrationPattern.Create(SizeMm, PitchUm, 20, null);
            var folder = Path.Combine(_dataFolder, "images");
            Directory.CreateDirectory(folder);
            var path = Path.Combine(folder, string.Create(CultureInfo.InvariantCulture, $"calibration-pattern-{SizeMm:0.###}mm-{PitchUm:0.###}um.png"));
            PngWriter.WriteMask(path, pattern.ToMask());
            if (_main.Job.LoadImage(path))
            {
                _main.Job.EditPitch(pattern.PitchUm);
            }

            PatternLines = [.. pattern.Describe()];
            XNominalMm = YNominalMm = pattern.MarkDistanceMm(pattern.MarkCount);
            Error = null;
        }
        catch (Exception ex) when (ex is CalibrationException or IOException or UnauthorizedAccessException or MachineBusyException)
        {
            Error = ex.Message;
        }
    }

    /// <summary>Solves squareness and scales from the measurements entered (0 = not measured).</summary>
    [RelayCommand]
    private void Solve()
    {
        var c = CultureInfo.InvariantCulture;
        try
        {
            var pattern = CalibrationPattern.Create(SizeMm, PitchUm, 20, null);
            var measurements = new CalibrationMeasurements
            {
                X = XMeasuredMm > 0 ? [new ScaleMeasurement(XNominalMm, XMeasuredMm)] : [],
                Y = YMeasuredMm > 0 ? [new ScaleMeasurement(YNominalMm, YMeasuredMm)] : [],
                SquareSideMm = pattern.SquareSideMm,
                DiagonalAcMm = DiagonalAcMm > 0 ? DiagonalAcMm : null,
                DiagonalBdMm = DiagonalBdMm > 0 ? DiagonalBdMm : null,
                GrooveAngleDegrees = AngleDegrees > 0 ? AngleDegrees : null,
            };
            var solution = CalibrationSolver.Solve(measurements);
            var solved = solution.Calibration;
            Solution = solution;
            SolutionLines =
            [
                $"Measured errors: {solved.Describe()}",
                string.Create(c, $"Uncertainty (1σ): ±{solved.SquarenessUncertaintyDegrees:0.#####}°, X ±{solved.ScaleXUncertaintyPpm:0.#} ppm, Y ±{solved.ScaleYUncertaintyPpm:0.#} ppm"),
                string.Create(c, $"Residuals: {solution.DegreesOfFreedom} degrees of freedom, length rms {solution.LengthRmsUm:0.###} µm"),
            ];
            Error = null;
        }
        catch (CalibrationException ex)
        {
            Solution = null;
            SolutionLines = [];
            Error = ex.Message;
        }
    }

    /// <summary>Stores the solution in the profile (refining a calibration the pattern was engraved with) and plans with it from now on.</summary>
    [RelayCommand(CanExecute = nameof(CanStore))]
    private void Store()
    {
        if (Solution is not { } solution)
        {
            return;
        }

        var profile = _main.Job.Profile;
        var solved = solution.Calibration;
        var stored = (profile.Calibration is { } previous ? previous.ThenResidual(solved) : solved) with
        {
            SquarenessUncertaintyDegrees = solved.SquarenessUncertaintyDegrees,
            ScaleXUncertaintyPpm = solved.ScaleXUncertaintyPpm,
            ScaleYUncertaintyPpm = solved.ScaleYUncertaintyPpm,
            Date = _time.GetUtcNow(),
        };
        Save(profile with { Calibration = stored }, $"stored: {stored.Describe()}");
    }

    private bool CanStore() => Solution is not null;

    /// <summary>Removes the calibration from the profile: later jobs are not compensated.</summary>
    [RelayCommand]
    private void Clear() => Save(_main.Job.Profile with { Calibration = null }, "calibration removed");

    private void Save(Core.Geometry.MachineProfile profile, string what)
    {
        var path = _main.Settings.ProfilePath ?? Path.Combine(_dataFolder, "machine-profile.json");
        try
        {
            profile.Calibration?.Validate();
            _main.SaveProfile(path, profile);
            Status = $"{what} -> {path}";
            Error = null;
            OnPropertyChanged(nameof(Current));
        }
        catch (Exception ex) when (ex is CalibrationException or IOException or UnauthorizedAccessException or MachineBusyException or ProfileException)
        {
            Error = ex.Message;
        }
    }
}
