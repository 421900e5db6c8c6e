using System.ComponentModel;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.App.Services;

/// <summary>
/// The open job as the panels share it: its values as one <see cref="JobSettings"/>, the planned job and what the rules
/// say of it, and the few ways a panel changes it (a preset, a log repeated, a job file opened). The test moves, the
/// presets, the log, the layers and the sweep depend on this, not on the view-model of the Image, Size and Process
/// panels that edits the job field by field.
/// </summary>
/// <remarks>Property changes are raised under the names below (and <see cref="PlanVersion"/> once per plan).</remarks>
public interface IJobSession : INotifyPropertyChanged
{
    /// <summary>The machine profile the job is planned for.</summary>
    MachineProfile Profile { get; }

    /// <summary>The open image or drawing file; null when none is open.</summary>
    string? ImagePath { get; }

    /// <summary>The open image's size and path; null for a drawing or nothing.</summary>
    ImageInfo? ImageInfo { get; }

    /// <summary>The open image's mask (black = burn); null for a drawing or nothing.</summary>
    BitMask? Mask { get; }

    /// <summary>Whether the open file is a drawing rather than an image.</summary>
    bool IsDrawing { get; }

    /// <summary>The planned image, or null.</summary>
    PreparedJob? Job { get; }

    /// <summary>The planned image or drawing as the one job type the run, the stage and the test moves take; null without a plan.</summary>
    EngraveJob? Engraving { get; }

    /// <summary>The job rules' errors by field (each stops Start).</summary>
    IReadOnlyDictionary<string, string> Errors { get; }

    /// <summary>Why the job cannot be changed now (a run, homing or a test move holds it); null when it can.</summary>
    string? LockedBecause { get; }

    /// <summary>Goes up whenever the plan changes.</summary>
    int PlanVersion { get; }

    /// <summary>Every value of the job at once.</summary>
    JobSettings ToSettings();

    /// <summary>The process values the job runs with.</summary>
    ProcessSettings Process();

    /// <summary>The plan options the job is planned with.</summary>
    PlanOptions PlanOptions();

    /// <summary>Sets every value at once and plans once (opening the settings' file when it is another).</summary>
    /// <exception cref="MachineBusyException">A run, homing or a test move holds the job.</exception>
    void Apply(JobSettings settings);

    /// <summary>Changes some values (<c>s =&gt; s with { ... }</c>) and plans once; the file and the aspect lock stay.</summary>
    /// <exception cref="MachineBusyException">A run, homing or a test move holds the job.</exception>
    void Change(Func<JobSettings, JobSettings> change);

    /// <summary>Opens an image or drawing; false (why stands in <see cref="Errors"/>) when it did not open.</summary>
    bool LoadImage(string path);
}
