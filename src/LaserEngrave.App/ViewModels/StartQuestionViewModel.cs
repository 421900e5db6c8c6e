using System.Globalization;
using CommunityToolkit.Mvvm.ComponentModel;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// What Start asks before it runs a job, with its numbers (the page and the API ask the same), and the question waiting
/// for its answer: Start anyway, or Cancel. It holds no other view-model: it is told the question and the job asked about.
/// </summary>
public sealed partial class StartQuestionViewModel : ObservableObject
{
    /// <summary>The long-run question's threshold at the first start: an hour.</summary>
    public const double DefaultAskAboveMinutes = 60;

    // The job the pending question was asked about (its plan's version, as its owner tells it).
    private object? _askedAbout;

    /// <summary>
    /// A run longer than this, minutes (the estimate, all passes), asks before it starts, in the page and through the API;
    /// the user's setting (<see cref="MainViewModel.SetAskAboveMinutes"/>), an hour until set.
    /// </summary>
    [ObservableProperty]
    public partial double AskAboveMinutes { get; set; } = DefaultAskAboveMinutes;

    /// <summary>The question Start asked, waiting for Start anyway or Cancel; null when none waits.</summary>
    [ObservableProperty]
    public partial string? Pending { get; private set; }

    /// <summary>
    /// The question for a run longer than <see cref="AskAboveMinutes"/>, or of pixels less than half the laser spot
    /// (each burns several times wider than it is); null when Start need not ask.
    /// </summary>
    public string? For(double? estimateSeconds, double? smallestPixelUm, double spotUm)
    {
        var reasons = new List<string>();
        if (estimateSeconds > AskAboveMinutes * 60)
        {
            reasons.Add($"it takes about {Components.Format.Duration(estimateSeconds.Value)}");
        }

        if (smallestPixelUm < spotUm / 2)
        {
            reasons.Add(string.Create(CultureInfo.InvariantCulture, $"its pixels of {smallestPixelUm:0.###} µm are much smaller than the {spotUm:0.#} µm laser spot, so each burns about {spotUm / smallestPixelUm:0} times wider than it is"));
        }

        return reasons.Count == 0 ? null : $"Start anyway? {char.ToUpperInvariant(reasons[0][0])}{string.Join("; and ", reasons)[1..]}.";
    }

    /// <summary>Asks <paramref name="question"/> about <paramref name="job"/> (a value that changes when the job does).</summary>
    internal void Ask(string? question, object job)
    {
        _askedAbout = job;
        Pending = question;
    }

    /// <summary>
    /// The answer "Start anyway" for <paramref name="job"/> as it is now: null when it is the job asked about (the
    /// question is answered); else the question is asked again for the job now (<paramref name="question"/>, none when it
    /// need not ask) and the line saying so is returned, and nothing must start.
    /// </summary>
    internal string? Answer(object job, string? question)
    {
        if (Pending is not null && !Equals(_askedAbout, job))
        {
            Ask(question, job);
            return question is null
                ? "the job changed while Start was asking: nothing started; press Start to run the job as it is now"
                : "the job changed while Start was asking: the question is asked again for the job as it is now";
        }

        Pending = null;
        return null;
    }

    /// <summary>The answer "Cancel": nothing starts.</summary>
    internal void Cancel() => Pending = null;
}
