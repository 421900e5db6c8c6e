using System.Globalization;
using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using CommunityToolkit.Mvvm.Messaging;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Marks;
using LaserEngrave.Simulator.Marks;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// The Mark panel: sample IDs (a code with its text beneath, or a text alone) in copies on a grid, numbered from the
/// counter, each code proven readable on the twin; the job it makes opens as the job of layers, which Start runs.
/// </summary>
public sealed partial class MarkViewModel : ObservableObject
{
    private readonly IMarkService _marks;
    private readonly Func<string, bool> _openJob;
    private readonly Func<string?> _sampleId;

    /// <param name="marks">Makes and checks the marks.</param>
    /// <param name="openJob">Opens a job file as the job of layers (the Layers panel's Open); false when it could not.</param>
    /// <param name="sampleId">
    /// The sample ID the run will be logged under (the Log panel's): what {sample} stands for, so a mark never names
    /// another sample than its run's log. None: no sample.
    /// </param>
    public MarkViewModel(IMarkService marks, Func<string, bool> openJob, Func<string?>? sampleId = null)
    {
        ArgumentNullException.ThrowIfNull(marks);
        ArgumentNullException.ThrowIfNull(openJob);
        _marks = marks;
        _openJob = openJob;
        _sampleId = sampleId ?? (() => null);
        RefreshCounter();

        // A completed run of marks advances the counter in the run service, after the log is in: the panel then shows
        // the next free number at once, not the one just burned (a weak registration: a panel gone is not kept).
        WeakReferenceMessenger.Default.Register<MarkViewModel, CounterAdvancedMessage>(this, static (mark, _) => mark.RefreshCounter());
    }

    /// <summary>Sent when a completed run of marks has advanced a sample counter.</summary>
    public sealed record CounterAdvancedMessage;

    /// <summary>The codes offered: value and label.</summary>
    public static IReadOnlyList<(string Value, string Label)> Codes { get; } = [("datamatrix", "Data Matrix"), ("qr", "QR code"), ("none", "Text alone")];

    [ObservableProperty]
    public partial string Text { get; set; } = "S-{n:000}";

    [ObservableProperty]
    public partial string Code { get; set; } = "datamatrix";

    /// <summary>The code's side without its quiet zone, mm.</summary>
    [ObservableProperty]
    public partial double SizeMm { get; set; } = 2;

    [ObservableProperty]
    public partial bool Label { get; set; } = true;

    [ObservableProperty]
    public partial double TextHeightMm { get; set; } = 0.4;

    [ObservableProperty]
    public partial double Copies { get; set; } = 10;

    [ObservableProperty]
    public partial double Columns { get; set; } = 5;

    /// <summary>From copy to copy along X and Y, mm.</summary>
    [ObservableProperty]
    public partial double PitchMm { get; set; } = 4;

    [ObservableProperty]
    public partial double OriginXMm { get; set; } = 10;

    [ObservableProperty]
    public partial double OriginYMm { get; set; } = 10;

    /// <summary>What {sample} stands for: the sample ID the run is logged under.</summary>
    public string? Sample => _sampleId();

    /// <summary>The counter's next free number: the first copy's of the next marks made.</summary>
    [ObservableProperty]
    public partial int NextNumber { get; private set; } = 1;

    [ObservableProperty]
    public partial IReadOnlyList<PlacedMark> Marks { get; private set; } = [];

    [ObservableProperty]
    public partial IReadOnlyList<ReadabilityVerdict> Verdicts { get; private set; } = [];

    [ObservableProperty]
    public partial double? EstimatedSeconds { get; private set; }

    /// <summary>The job made, opened as the job of layers; null before, or when a code did not read.</summary>
    [ObservableProperty]
    public partial string? JobFile { get; private set; }

    [ObservableProperty]
    public partial string? Error { get; private set; }

    /// <summary>One line beside the estimate: every code reads on the twin, or which does not.</summary>
    public string? Verdict => Verdicts.Count == 0
        ? null
        : Verdicts.FirstOrDefault(v => !v.Reads) is { } bad
            ? string.Create(CultureInfo.InvariantCulture, $"\"{bad.Text}\" does not read on the twin ({bad.ModulesRight} of {bad.Modules} modules right): make the mark larger")
            : string.Create(CultureInfo.InvariantCulture, $"{(Verdicts.Count == 1 ? "the code reads" : $"all {Verdicts.Count} codes read")} on the twin; worst module {Verdicts.Min(v => v.WorstModulePercent):0} % as it should be, modules {Verdicts[0].ModuleUm:0.#} µm = {Verdicts[0].ModuleUm / Verdicts[0].SpotDiameterUm:0.#} spots");

    /// <summary>The numbers of the marks made and not yet burned, as the panel says them; null before any are made.</summary>
    public string? MadeNumbers => Marks.Count == 0
        ? null
        : (Marks.Min(m => m.Number), Marks.Max(m => m.Number)) is var (first, last) && first == last
            ? string.Create(CultureInfo.InvariantCulture, $"These marks: number {first}")
            : string.Create(CultureInfo.InvariantCulture, $"These marks: numbers {first}–{last}");

    /// <summary>"1 mark", "10 marks": the marks made.</summary>
    public string? MadeCount => Marks.Count == 0
        ? null
        : Marks.Select(m => m.Number).Distinct().Count() is var n && n == 1 ? "1 mark" : string.Create(CultureInfo.InvariantCulture, $"{n} marks");

    /// <summary>Makes the marks, burns every code on the twin and reads it back; when all read, opens the job as the job of layers.</summary>
    [RelayCommand(IncludeCancelCommand = true)]
    private async Task MakeAsync(CancellationToken cancellationToken)
    {
        Error = null;
        JobFile = null;
        RefreshCounter();
        MarkSpec spec;
        try
        {
            spec = Spec();
        }
        catch (MarkException ex)
        {
            Error = ex.Message;
            return;
        }

        try
        {
            var result = await _marks.MakeAsync(spec, Sample, check: true, cancellationToken);
            Marks = result.Marks;
            OnPropertyChanged(nameof(MadeNumbers));
            OnPropertyChanged(nameof(MadeCount));
            Verdicts = result.Verdicts;
            EstimatedSeconds = result.EstimatedSeconds;
            OnPropertyChanged(nameof(Verdict));
            if (result.JobFile is { } job)
            {
                JobFile = job;
                if (!_openJob(job))
                {
                    Error = $"{job}: made, but the Layers panel could not open it";
                }
            }
        }
        catch (MarkException ex)
        {
            Error = ex.Message;
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            // A full disk or a read-only data folder: said in the panel, not left to end the page's connection.
            Error = $"the marks could not be saved: {ex.Message}";
        }
    }

    /// <summary>Reads the counter again (a run of marks that completed has advanced it).</summary>
    public void RefreshCounter()
    {
        try
        {
            NextNumber = _marks.NextNumber();
        }
        catch (MarkException ex)
        {
            Error = ex.Message;
        }
    }

    /// <summary>
    /// The panel's boxes as a mark. Only what a number box cannot say is refused here (a count that is not whole); every
    /// range is MarkLayout's rule, refused by the service in the panel's words, as the command line and marks files are.
    /// </summary>
    private MarkSpec Spec()
    {
        var code = MarkFile.ParseCode(Code);
        return new MarkSpec
        {
            Text = Text ?? string.Empty,
            Code = code,
            SizeMm = code is null ? null : SizeMm,
            Label = Label,
            TextHeightMm = TextHeightMm,
            Copies = Whole(Copies, "copies"),
            Columns = Whole(Columns, "columns"),
            PitchXMm = PitchMm,
            PitchYMm = PitchMm,
            Origin = new OriginMm(OriginXMm, OriginYMm),
        };
    }

    private static int Whole(double value, string name) =>
        value == Math.Floor(value) && Math.Abs(value) <= int.MaxValue ? (int)value : throw new MarkException(string.Create(CultureInfo.InvariantCulture, $"{name} {value:G6} must be a whole number 1..{MarkSpec.MaxCopies}"));
}
