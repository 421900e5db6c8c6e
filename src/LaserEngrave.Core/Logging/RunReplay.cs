using LaserEngrave.Core.Jobs;

namespace LaserEngrave.Core.Logging;

/// <summary>Turns a logged run back into the job that repeats it, refusing when the image is gone or has changed.</summary>
public static class RunReplay
{
    /// <summary>
    /// The job of <paramref name="record"/>: same image, mask, size, origin, plan, process and profile. Throws
    /// <see cref="RunLogException"/> when the image is not at its logged path or its SHA-256 differs from the logged one.
    /// </summary>
    public static JobSpec ToJobSpec(RunRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        var image = record.Image;
        if (!File.Exists(image.Path))
        {
            throw new RunLogException($"{image.Path}: the run's image is not there any more (moved or deleted); put it back to repeat the run");
        }

        string hash;
        try
        {
            hash = PreparedJob.HashFile(image.Path);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            throw new RunLogException($"{image.Path}: cannot read the run's image: {ex.Message}", ex);
        }

        if (!string.Equals(hash, image.Sha256, StringComparison.OrdinalIgnoreCase))
        {
            throw new RunLogException(
                $"{image.Path}: the image has changed since the run (SHA-256 {Short(hash)}... now, {Short(image.Sha256)}... logged); refusing to repeat it");
        }

        return new JobSpec
        {
            ImagePath = image.Path,
            Mask = record.Mask,
            Size = record.Geometry.Size.ToSizeSpec(),
            Origin = new Geometry.OriginMm(record.Geometry.OriginXMm, record.Geometry.OriginYMm),
            Plan = record.Plan,
            Process = record.Process,
            Profile = record.Profile,
            Passes = Math.Clamp(record.Passes, 1, JobSpec.MaxPasses),
        };
    }

    private static string Short(string hash) => hash.Length > 12 ? hash[..12] : hash;
}
