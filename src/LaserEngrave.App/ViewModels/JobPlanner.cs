using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// What the Image, Size and Process panels show after a change, made apart from the view-model that holds their
/// values: the planned image or drawing, the errors and warnings by field, and the sizes the fields follow.
/// </summary>
/// <param name="Job">The planned image, or null.</param>
/// <param name="Drawing">The planned drawing, or null.</param>
/// <param name="Errors">The errors by field (each stops Start).</param>
/// <param name="Warnings">The warnings by field (the job can still run).</param>
/// <param name="WidthMm">The width the width field follows to, or null to leave it.</param>
/// <param name="HeightMm">The height the height field follows to, or null to leave it.</param>
/// <param name="PitchUm">The pitch the pitch field follows to, or null to leave it.</param>
internal sealed record JobPlan(
    PreparedJob? Job,
    PreparedDrawing? Drawing,
    Dictionary<string, string> Errors,
    Dictionary<string, string> Warnings,
    double? WidthMm = null,
    double? HeightMm = null,
    double? PitchUm = null);

/// <summary>Plans the job the fields describe: by the job rules first (the command line's and the files' too), then the planners.</summary>
internal static class JobPlanner
{
    /// <summary>Each value checked by the job rules, so its message stands beside its field (the page has one origin field for both coordinates).</summary>
    public static Dictionary<string, string> FieldErrors(JobSettings settings, MachineProfile profile)
    {
        var errors = new Dictionary<string, string>();
        foreach (var problem in JobRules.Check(settings, MachineLimits.Of(profile)))
        {
            Add(errors, problem.Field is JobField.OriginX or JobField.OriginY ? JobViewModel.OriginField : problem.Field, problem.Message);
        }

        return errors;
    }

    /// <summary>Plans an image's mask; <paramref name="errors"/> (the fields' and the image's) stop it before the planners run.</summary>
    /// <param name="prepare">Plans a mask (a plan made while the image was opened may serve instead).</param>
    public static JobPlan Image(JobSpec spec, SizeMode sizeMode, BitMask? mask, ImageInfo? info, Dictionary<string, string> errors, Func<JobSpec, ImageInfo, BitMask, PreparedJob> prepare)
    {
        var warnings = new Dictionary<string, string>();
        PreparedJob? job = null;
        if (mask is not null && info is not null && errors.Count == 0)
        {
            try
            {
                job = prepare(spec with { ImagePath = info.Path }, info, mask);
            }
            catch (GeometryException ex)
            {
                errors[SizeField(sizeMode)] = ex.Message;
            }
            catch (PlanException ex)
            {
                errors[JobViewModel.OverscanField] = ex.Message;
            }
        }

        if (job is null)
        {
            return new JobPlan(null, null, errors, warnings);
        }

        if (JobRules.Check(job) is { } refused)
        {
            // The command line or the engine would refuse this job: an error beside the field to change, so Start stays disabled.
            errors[refused.Field] = refused.Message;
        }

        // Off the travel is refused, typed or dropped, as the command line and Start refuse it: the rule's sentence beside the origin.
        var outside = JobRules.Placement(job);
        if (outside is not null)
        {
            Add(errors, JobViewModel.OriginField, outside);
        }

        foreach (var warning in job.Warnings.Where(w => w.Kind is not (JobWarningKind.PitchBelowMicrostep or JobWarningKind.PixelTooShortForTheGate or JobWarningKind.BurstTooLongForTheWatchdog)
            && !(outside is not null && job.Geometry.Warnings.Contains(w))))
        {
            var field = warning.Kind switch
            {
                JobWarningKind.OutsideTravel => JobViewModel.OriginField,
                JobWarningKind.OverscanClamped => JobViewModel.OverscanField,
                JobWarningKind.PulseGaps or JobWarningKind.PixelUnderOnePulse => JobViewModel.PulsesField,
                _ => JobViewModel.PitchField,
            };
            Add(warnings, field, warning.Message);
        }

        // The fields that follow show what the job will really be.
        var g = job.Geometry;
        return new JobPlan(
            job,
            null,
            errors,
            warnings,
            sizeMode != SizeMode.Width ? Math.Round(g.RequestedWidthMm, 4) : null,
            sizeMode != SizeMode.Height ? Math.Round(g.RequestedHeightMm, 4) : null,
            sizeMode != SizeMode.Pitch ? Math.Round(g.PitchUm, 4) : null);
    }

    /// <summary>Plans a drawing: by the width typed (width mode), else in its own units; placed at the origin.</summary>
    public static JobPlan Drawing(JobSpec spec, SizeMode sizeMode, double widthMm, VectorOptions options, Dictionary<string, string> errors)
    {
        var warnings = new Dictionary<string, string>();
        PreparedDrawing? drawing = null;
        if (errors.Count == 0)
        {
            try
            {
                spec = spec with { Size = SizeSpec.Width(widthMm > 0 ? widthMm : 1) };
                drawing = sizeMode == SizeMode.Width && widthMm > 0 ? PreparedDrawing.Prepare(spec, options) : PreparedDrawing.PrepareOwnSize(spec, options);
            }
            catch (DrawingException ex)
            {
                errors[JobViewModel.ImageField] = ex.Message;
            }
            catch (GeometryException ex)
            {
                errors[JobViewModel.WidthField] = ex.Message;
            }
            catch (PlanException ex)
            {
                errors[JobViewModel.ImageField] = ex.Message;
            }
        }

        if (drawing is null)
        {
            return new JobPlan(null, null, errors, warnings);
        }

        if (drawing.Warnings.Count > 0)
        {
            warnings[JobViewModel.ImageField] = string.Join("; ", drawing.Warnings);
        }

        // Off the travel is refused, typed or dropped, as the command line and Start refuse it.
        if (JobRules.Placement(drawing) is { } outside)
        {
            errors[JobViewModel.OriginField] = outside;
        }

        return new JobPlan(null, drawing, errors, warnings, Math.Round(drawing.Plan.WidthMm, 4), Math.Round(drawing.Plan.HeightMm, 4));
    }

    private static string SizeField(SizeMode mode) => mode switch
    {
        SizeMode.Height => JobViewModel.HeightField,
        SizeMode.Pitch => JobViewModel.PitchField,
        _ => JobViewModel.WidthField,
    };

    private static void Add(Dictionary<string, string> messages, string field, string message) =>
        messages[field] = messages.TryGetValue(field, out var before) ? before + "; " + message : message;
}
