using System.Globalization;
using System.Threading.Channels;
using LaserEngrave.Devices.Scheduling;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Wire.Scheduling;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Devices.Zaber;

/// <summary>The one owner of a Zaber chain's serial link: frames replies and hands each to the request waiting for it.</summary>
/// <remarks>
/// Its <see cref="SerialChannel{TMessage}"/> reads the link and assembles 6-byte frames with a <see cref="ZaberFramer"/>
/// (dropping an unfinished frame whose bytes arrived further apart than the partial-frame timeout); the connection
/// matches each reply to a pending request by device and command; both axes share the wire, so a reply for one
/// reaches its own waiter while the other is still moving. Reply-only frames (8, 9, 10) come out as
/// <see cref="UnsolicitedReply"/>. Every wait runs on the given <see cref="System.TimeProvider"/>. After garbage or a
/// timeout the connection waits out the gap, drops partial bytes and confirms the line with Echo Data.
/// </remarks>
public sealed class ZaberConnection : IAsyncDisposable
{
    private const int FirstEchoNonce = 0x4C450000;

    private static readonly HashSet<ZaberCommand> ReplyOnlyCommands =
        [ZaberCommand.MoveTracking, ZaberCommand.LimitActive, ZaberCommand.ManualMoveTracking];

    // Move commands that pre-empt one another on a device (Home cannot be pre-empted: the device answers Busy).
    private static readonly HashSet<ZaberCommand> PreemptiveMoves =
        [(ZaberCommand)18, ZaberCommand.MoveAbsolute, ZaberCommand.MoveRelative, ZaberCommand.MoveAtConstantSpeed, ZaberCommand.Stop];

    private readonly SerialChannel<ZaberFrame> _channel;
    private readonly ZaberFramer _framer;
    private readonly TimeProvider _time;
    private readonly Lock _gate = new();
    private readonly AsyncLock _sendLock;
    private readonly CancellationTokenSource _stop = new();
    private readonly List<PendingRequest> _pending = [];
    private readonly List<PendingBroadcast> _broadcasts = [];
    private readonly Dictionary<byte, string> _labels = [];
    private readonly HashSet<byte> _knownDevices = [];
    private readonly HashSet<(byte Device, byte Command)> _expectedReplies = [];
    private readonly Queue<double> _roundTrips = new();
    private long _roundTripsRecorded;
    private long _sequence;
    private int _echoNonce = FirstEchoNonce;
    private bool _resyncRunning;
    private Task _resync = Task.CompletedTask;
    private bool _closed;
    private int _disposed;
    private volatile Task<long?> _lineWritten = Task.FromResult<long?>(null);

    public ZaberConnection(ISerialLink link, TimeProvider? timeProvider = null, ZaberConnectionOptions? options = null)
    {
        ArgumentNullException.ThrowIfNull(link);
        _time = timeProvider ?? TimeProvider.System;
        Options = options ?? new ZaberConnectionOptions();
        _framer = new ZaberFramer(Options.PartialFrameTimeout, _time, OnPartialFrameDropped);
        _channel = new SerialChannel<ZaberFrame>(link, _framer, _time, OnFrame, Close);
        _sendLock = _channel.SendLock;
        _channel.Start();
    }

    /// <summary>
    /// The latest round trips of commands that reply at once (settings, Return commands, Echo), ms from the write's end
    /// to the reply's hand-over, at most <see cref="RoundTripsKept"/>: how far the line's latencies (and the host's own
    /// lateness) spread, without sending anything more. Preflight compares their spread with the profile's.
    /// </summary>
    public IReadOnlyList<double> RecentRoundTripsMs
    {
        get
        {
            lock (_gate)
            {
                return [.. _roundTrips];
            }
        }
    }

    /// <summary>How many round trips have been recorded since the connection opened (the latest are <see cref="RecentRoundTripsMs"/>).</summary>
    public long RoundTripsRecorded
    {
        get
        {
            lock (_gate)
            {
                return _roundTripsRecorded;
            }
        }
    }

    /// <summary>How many round trips <see cref="RecentRoundTripsMs"/> keeps.</summary>
    public const int RoundTripsKept = 64;

    /// <summary>Reply-only frames (Move Tracking, Limit Active, Manual Move Tracking) and errors no request is waiting for.</summary>
    /// <remarks>Raised on the reader loop: handlers must be quick and must not wait for replies.</remarks>
    public event EventHandler<ZaberReplyEventArgs>? UnsolicitedReply;

    /// <summary>Noise, stale replies and resynchronisation, for logs and diagnostics.</summary>
    public event EventHandler<ZaberLineEventArgs>? LineEvent;

    public string PortName => _channel.Name;

    public ZaberConnectionOptions Options { get; }

    public TimeProvider TimeProvider => _time;

    /// <summary>False once the link was lost or the connection disposed.</summary>
    public bool IsOpen
    {
        get
        {
            lock (_gate)
            {
                return !_closed;
            }
        }
    }

    /// <summary>
    /// Completes when the request asked for last (the call that returned just before this is read) has been written,
    /// with the time its write completed as a timestamp of the connection's clock; null when it was never written.
    /// </summary>
    public Task<long?> LineWritten => _lineWritten;

    /// <summary>True while bytes that arrived are still on their way to their waiters (unread, or being framed and handed on).</summary>
    public bool IsReceiving => _channel.IsReceiving;

    /// <summary>Bytes taken from the link so far (tests use it to know the reader has seen what was sent).</summary>
    internal long BytesReceived => _channel.BytesReceived;

    /// <summary>Names a device in messages ("device 1 (X)") and marks it as one that may reply.</summary>
    public void SetDeviceLabel(byte device, string? label)
    {
        lock (_gate)
        {
            _knownDevices.Add(device);
            if (string.IsNullOrEmpty(label))
            {
                _labels.Remove(device);
            }
            else
            {
                _labels[device] = label;
            }
        }
    }

    /// <summary>"device 1 (X)" or "device 3".</summary>
    public string DescribeDevice(byte device)
    {
        lock (_gate)
        {
            return _labels.TryGetValue(device, out var label) ? $"device {device} ({label})" : $"device {device}";
        }
    }

    /// <summary>Sends a command and waits, up to <see cref="ZaberConnectionOptions.CommandTimeout"/>, for its reply.</summary>
    public Task<ZaberFrame> RequestAsync(ZaberFrame request, CancellationToken cancellationToken) =>
        RequestAsync(request, Options.CommandTimeout, cancellationToken);

    /// <summary>Sends a command to one device and waits for its reply.</summary>
    /// <exception cref="ZaberException">The device answered with an Error reply.</exception>
    /// <exception cref="DeviceTimeoutException">No reply within <paramref name="timeout"/>.</exception>
    /// <exception cref="LinkLostException">The link closed before the reply.</exception>
    /// <exception cref="ZaberInterruptedException">A later move or Stop pre-empted this move.</exception>
    public Task<ZaberFrame> RequestAsync(ZaberFrame request, TimeSpan timeout, CancellationToken cancellationToken) =>
        RequestCoreAsync(request, timeout, holdLine: false, resynchroniseOnTimeout: true, cancellationToken);

    /// <summary>Sends a command that gets no reply (Reset).</summary>
    public async Task SendAsync(ZaberFrame command, CancellationToken cancellationToken)
    {
        await _sendLock.WaitAsync(cancellationToken);
        try
        {
            lock (_gate)
            {
                ThrowIfClosed(command);
            }

            await WriteFrameAsync(command, cancellationToken);
        }
        finally
        {
            _sendLock.Release();
        }
    }

    /// <summary>Sends a command to device 0 (every device) and collects every reply until the line goes quiet.</summary>
    /// <param name="command">The command every device executes.</param>
    /// <param name="data">Its data.</param>
    /// <param name="firstReplyTimeout">How long to wait for the first reply; later ones end after <see cref="ZaberConnectionOptions.BroadcastQuietPeriod"/> of quiet.</param>
    /// <param name="cancellationToken">Cancels the wait.</param>
    /// <returns>Every reply, Error replies included, in arrival order; empty when nobody answered.</returns>
    public async Task<IReadOnlyList<ZaberFrame>> BroadcastAsync(ZaberCommand command, int data, TimeSpan firstReplyTimeout, CancellationToken cancellationToken)
    {
        var frame = new ZaberFrame(0, command, data);
        var replyCommand = command == ZaberCommand.ReturnSetting ? (byte)data : (byte)command;
        var broadcast = new PendingBroadcast(replyCommand);
        await _sendLock.WaitAsync(cancellationToken);
        try
        {
            lock (_gate)
            {
                ThrowIfClosed(frame);
                _broadcasts.Add(broadcast);
            }

            await WriteFrameAsync(frame, cancellationToken);
        }
        catch
        {
            lock (_gate)
            {
                _broadcasts.Remove(broadcast);
            }

            throw;
        }
        finally
        {
            _sendLock.Release();
        }

        var replies = new List<ZaberFrame>();
        try
        {
            var wait = firstReplyTimeout;
            while (replies.Count < 254)
            {
                bool more;
                using var quiet = new CancellationTokenSource(wait, _time);
                using var either = CancellationTokenSource.CreateLinkedTokenSource(cancellationToken, quiet.Token);
                try
                {
                    more = await broadcast.Replies.Reader.WaitToReadAsync(either.Token);
                }
                catch (OperationCanceledException) when (quiet.IsCancellationRequested && !cancellationToken.IsCancellationRequested)
                {
                    break;
                }

                if (!more)
                {
                    break;
                }

                while (broadcast.Replies.Reader.TryRead(out var reply))
                {
                    replies.Add(reply);
                }

                wait = Options.BroadcastQuietPeriod;
            }
        }
        finally
        {
            lock (_gate)
            {
                _broadcasts.Remove(broadcast);
            }
        }

        lock (_gate)
        {
            if (_closed)
            {
                throw LinkLost(frame, replyExpected: true);
            }
        }

        return replies;
    }

    /// <summary>Waits until the line has been quiet for the partial-frame timeout, drops partial bytes, and checks
    /// that <paramref name="device"/> echoes Echo Data.</summary>
    /// <returns>True when the echo came back (or the device answered at all): frames are aligned again.</returns>
    public Task<bool> ResynchroniseAsync(byte device, CancellationToken cancellationToken) => ResynchroniseCoreAsync(device, cancellationToken);

    public async ValueTask DisposeAsync()
    {
        if (Interlocked.Exchange(ref _disposed, 1) != 0)
        {
            return;
        }

        _stop.Cancel();
        await _channel.DisposeAsync();
        try
        {
            await _resync;
        }
        catch (OperationCanceledException)
        {
            // The resynchronisation was cut short by the disposal itself.
        }

        _stop.Dispose();
    }

    internal void AddKnownDevice(byte device)
    {
        lock (_gate)
        {
            _knownDevices.Add(device);
        }
    }

    /// <param name="request">The command.</param>
    /// <param name="timeout">How long to wait for its reply.</param>
    /// <param name="holdLine">Keep the send lock until the reply (Renumber).</param>
    /// <param name="resynchroniseOnTimeout">Confirm the line with Echo Data after a timeout.</param>
    /// <param name="cancellationToken">Cancels the wait.</param>
    /// <param name="preempts">
    /// Whether a move pre-empts the device's move still waiting for its reply (true), or is sent to arrive after that
    /// move ended, its reply still on the way (false: both wait for their own replies, matched by position).
    /// </param>
    internal async Task<ZaberFrame> RequestCoreAsync(ZaberFrame request, TimeSpan timeout, bool holdLine, bool resynchroniseOnTimeout, CancellationToken cancellationToken, bool preempts = true)
    {
        if (request.Device == 0)
        {
            throw new ArgumentException($"{PortName}: {ZaberCommandText.Describe(request)} to device 0 gets one reply per device; use BroadcastAsync", nameof(request));
        }

        if (request.Command is ZaberCommand.Reset)
        {
            throw new ArgumentException($"{PortName}: Reset gets no reply; use SendAsync", nameof(request));
        }

        var pending = new PendingRequest(request);
        List<PendingRequest>? interrupted = null;
        var lineWritten = new TaskCompletionSource<long?>(TaskCreationOptions.RunContinuationsAsynchronously);
        _lineWritten = lineWritten.Task;
        await _sendLock.WaitAsync(cancellationToken);
        var lineHeld = true;
        try
        {
            lock (_gate)
            {
                ThrowIfClosed(request);
                pending.Sequence = ++_sequence;
                _knownDevices.Add(request.Device);
                _knownDevices.Add(pending.ReplyDevice);
                _expectedReplies.Add((pending.ReplyDevice, pending.ReplyCommand));
                if (preempts && PreemptiveMoves.Contains(request.Command))
                {
                    interrupted = Preempt(request);
                }

                _pending.Add(pending);
            }

            FailInterrupted(interrupted, request);
            long written;
            try
            {
                written = await WriteFrameAsync(request, cancellationToken);
                lineWritten.TrySetResult(written);
            }
            catch
            {
                Remove(pending);
                lineWritten.TrySetResult(null);
                throw;
            }

            if (!holdLine)
            {
                _sendLock.Release();
                lineHeld = false;
            }

            try
            {
                var reply = await Signals.WaitAsync(pending.Completion, timeout, _time, () => _channel.IsReceiving, cancellationToken);
                if (!RepliesOnCompletion.Contains(request.Command) && !holdLine)
                {
                    // To the reply's arrival, not to when this waiter ran: a host late to read is no latency of the line.
                    RecordRoundTrip(_time.GetElapsedTime(written, pending.Arrived is { } arrived && arrived >= written ? arrived : _time.GetTimestamp()).TotalMilliseconds);
                }

                return reply;
            }
            catch (TimeoutException)
            {
                // The timer completed the request before any reply did: it is over, whatever comes later.
                Remove(pending);
                if (resynchroniseOnTimeout)
                {
                    StartResynchronising(request.Device);
                }

                throw new DeviceTimeoutException(
                    $"{PortName}: {DescribeDevice(request.Device)} did not reply to {ZaberCommandText.Describe(request)} within {FormatSpan(timeout)}");
            }
            catch (OperationCanceledException)
            {
                Remove(pending);
                throw;
            }
        }
        finally
        {
            if (lineHeld)
            {
                _sendLock.Release();
            }

            lineWritten.TrySetResult(null);
        }
    }

    // Moves (and Home, Stop) reply when they end, so their round trips say nothing of the line's latency.
    private static readonly HashSet<ZaberCommand> RepliesOnCompletion =
        [ZaberCommand.Home, (ZaberCommand)18, ZaberCommand.MoveAbsolute, ZaberCommand.MoveRelative, ZaberCommand.Stop, ZaberCommand.Renumber];

    private void RecordRoundTrip(double ms)
    {
        lock (_gate)
        {
            _roundTrips.Enqueue(ms);
            _roundTripsRecorded++;
            while (_roundTrips.Count > RoundTripsKept)
            {
                _roundTrips.Dequeue();
            }
        }
    }

    private static string FormatSpan(TimeSpan span) => span < TimeSpan.FromSeconds(2)
        ? $"{span.TotalMilliseconds.ToString("0", CultureInfo.InvariantCulture)} ms"
        : $"{span.TotalSeconds.ToString("0.0", CultureInfo.InvariantCulture)} s";

    private static ZaberCommand? CommandForErrorCode(int code) => code switch
    {
        >= 4000 and < 4100 => ZaberCommand.SetDeviceMode,
        1600 or 1601 => (ZaberCommand)16,
        1700 => (ZaberCommand)17,
        1800 or 1801 => (ZaberCommand)18,
        2146 => ZaberCommand.MoveRelative,
        > 0 and < 255 => (ZaberCommand)code,
        _ => null,
    };

    // Returns when the write completed (the round trip counts from there, not from when it was asked for).
    private Task<long> WriteFrameAsync(ZaberFrame frame, CancellationToken cancellationToken) =>
        _channel.WriteAsync(frame.ToBytes(), $"{PortName}: cannot send {ZaberCommandText.Describe(frame)} to {DescribeTarget(frame.Device)}", cancellationToken);

    private string DescribeTarget(byte device) => device == 0 ? "every device" : DescribeDevice(device);

    private List<PendingRequest>? Preempt(ZaberFrame request)
    {
        List<PendingRequest>? interrupted = null;
        foreach (var other in _pending)
        {
            if (!other.Interrupted && other.Request.Device == request.Device && PreemptiveMoves.Contains(other.Request.Command))
            {
                // Kept in the list as a zombie so that a late reply to it is not taken for the new command's.
                other.Interrupted = true;
                (interrupted ??= []).Add(other);
            }
        }

        return interrupted;
    }

    private void FailInterrupted(List<PendingRequest>? interrupted, ZaberFrame by)
    {
        foreach (var request in interrupted ?? [])
        {
            request.Completion.TrySetException(new ZaberInterruptedException(
                $"{PortName}: {DescribeDevice(request.Request.Device)} {ZaberCommandText.Describe(request.Request)} was interrupted by {ZaberCommandText.Describe(by)}"));
        }
    }

    private bool Remove(PendingRequest pending)
    {
        lock (_gate)
        {
            return _pending.Remove(pending);
        }
    }

    private void ThrowIfClosed(ZaberFrame frame)
    {
        if (_closed)
        {
            throw LinkLost(frame, replyExpected: false);
        }
    }

    private LinkLostException LinkLost(ZaberFrame frame, bool replyExpected)
    {
        var what = _channel.ClosedState;
        return _channel.LinkLost(replyExpected
            ? $"{PortName}: {what} while waiting for {DescribeTarget(frame.Device)} to reply to {ZaberCommandText.Describe(frame)}"
            : $"{PortName}: cannot send {ZaberCommandText.Describe(frame)} to {DescribeTarget(frame.Device)}: {what}");
    }

    private void Close(Exception? reason)
    {
        List<(PendingRequest Request, LinkLostException Error)> failed = [];
        lock (_gate)
        {
            if (_closed)
            {
                return;
            }

            _closed = true;
            foreach (var pending in _pending)
            {
                failed.Add((pending, LinkLost(pending.Request, replyExpected: true)));
            }

            _pending.Clear();
            foreach (var broadcast in _broadcasts)
            {
                broadcast.Replies.Writer.TryComplete();
            }
        }

        foreach (var (request, error) in failed)
        {
            request.Completion.TrySetException(error);
        }
    }

    private void OnFrame(ZaberFrame frame)
    {
        List<Action>? after = null;
        lock (_gate)
        {
            Dispatch(frame, ref after);
        }

        foreach (var action in after ?? [])
        {
            action();
        }
    }

    private void OnPartialFrameDropped(byte[] dropped) => LineEvent?.Invoke(this, new ZaberLineEventArgs(
        ZaberLineEvent.PartialFrameDropped, string.Create(CultureInfo.InvariantCulture, $"{PortName}: dropped {dropped.Length} byte(s) of an unfinished frame ({Convert.ToHexString(dropped)}) after a gap of at least {_framer.LastDropGap.TotalMilliseconds:0.0} ms")));

    private void Dispatch(ZaberFrame frame, ref List<Action>? after)
    {
        var device = frame.Device;
        var known = _knownDevices.Contains(device) || (_broadcasts.Count > 0 && device is > 0 and < 255);
        if (frame.Command == ZaberCommand.Error)
        {
            var target = FindErrorTarget(device, frame.Data);
            if (target is not null)
            {
                _pending.Remove(target);
                ExpireZombies(target);
                target.Completion.TrySetException(Refused(target.Request, frame.Data));
            }
            else if (_broadcasts.Count > 0 && device is > 0 and < 255)
            {
                _knownDevices.Add(device);
                _broadcasts[0].Replies.Writer.TryWrite(frame);
            }
            else if (known)
            {
                (after ??= []).Add(() => UnsolicitedReply?.Invoke(this, new ZaberReplyEventArgs(frame)));
            }
            else
            {
                Garbage(frame, ref after);
            }

            return;
        }

        if (ReplyOnlyCommands.Contains(frame.Command))
        {
            if (known)
            {
                (after ??= []).Add(() => UnsolicitedReply?.Invoke(this, new ZaberReplyEventArgs(frame)));
            }
            else
            {
                Garbage(frame, ref after);
            }

            return;
        }

        var request = FindReplyTarget(frame);
        if (request is not null)
        {
            _pending.Remove(request);
            if (request.Interrupted)
            {
                Note(ref after, ZaberLineEvent.UnmatchedReply,
                    $"{PortName}: late reply {frame} to the interrupted {ZaberCommandText.Describe(request.Request)} of {DescribeDevice(request.Request.Device)}");
            }
            else
            {
                ExpireZombies(request);
                var replaced = ReplacedMoves(request);
                request.Arrived = _channel.CurrentArrival;
                request.Completion.TrySetResult(frame);
                foreach (var earlier in replaced)
                {
                    earlier.Completion.TrySetException(new ZaberInterruptedException(
                        $"{PortName}: {DescribeDevice(earlier.Request.Device)} {ZaberCommandText.Describe(earlier.Request)} was replaced by the next move before it reported its end"));
                }
            }

            return;
        }

        var broadcast = _broadcasts.Find(b => b.ReplyCommand == (byte)frame.Command);
        if (broadcast is not null && device is > 0 and < 255)
        {
            _knownDevices.Add(device);
            broadcast.Replies.Writer.TryWrite(frame);
            return;
        }

        if (known && _expectedReplies.Contains((device, (byte)frame.Command)))
        {
            Note(ref after, ZaberLineEvent.UnmatchedReply, $"{PortName}: reply {frame} from {DescribeDevice(device)} matches no pending request (late or duplicate)");
            return;
        }

        Garbage(frame, ref after);
    }

    private PendingRequest? FindReplyTarget(ZaberFrame frame)
    {
        PendingRequest? oldestLive = null;
        PendingRequest? exactMove = null;
        PendingRequest? zombie = null;
        foreach (var pending in _pending)
        {
            if (pending.ReplyDevice != frame.Device || pending.ReplyCommand != (byte)frame.Command
                || (pending.ExpectedData is { } data && data != frame.Data))
            {
                continue;
            }

            if (pending.Interrupted)
            {
                zombie ??= pending;
                continue;
            }

            oldestLive ??= pending;
            if (frame.Command == ZaberCommand.MoveAbsolute && pending.Request.Data == frame.Data)
            {
                exactMove ??= pending;
            }
        }

        // A Move Absolute ends exactly on its target, so a reply elsewhere belongs to an interrupted move.
        if (exactMove is not null)
        {
            return exactMove;
        }

        if (zombie is not null && (oldestLive is null || frame.Command == ZaberCommand.MoveAbsolute))
        {
            return zombie;
        }

        return oldestLive;
    }

    private PendingRequest? FindErrorTarget(byte device, int code)
    {
        var live = _pending.Where(p => !p.Interrupted && p.Request.Device == device).ToList();
        if (live.Count == 0)
        {
            return null;
        }

        // Busy refuses the command just sent; other codes are usually the number of the refused command.
        if (code == ZaberErrorCodes.Busy)
        {
            return live[^1];
        }

        var command = CommandForErrorCode(code);
        return live.Find(p => p.Request.Command == command) ?? live[0];
    }

    // A move sent to arrive after the one before ended (RequestCoreAsync with preempts: false) can still catch it in its
    // last moments and replace it, and a replaced move may never reply (the protocol leaves it open): once a later move
    // of the device has reported its end, the earlier ones waiting count as replaced.
    private List<PendingRequest> ReplacedMoves(PendingRequest answered)
    {
        if (!PreemptiveMoves.Contains(answered.Request.Command))
        {
            return [];
        }

        var replaced = _pending.Where(p => !p.Interrupted && p.Request.Device == answered.Request.Device
            && p.Sequence < answered.Sequence && PreemptiveMoves.Contains(p.Request.Command)).ToList();
        _pending.RemoveAll(replaced.Contains);
        return replaced;
    }

    // A device answers in order, so once a later request of the device is answered, an interrupted one never will be.
    private void ExpireZombies(PendingRequest answered) =>
        _pending.RemoveAll(p => p.Interrupted && p.Request.Device == answered.Request.Device && p.Sequence < answered.Sequence);

    private ZaberException Refused(ZaberFrame request, int code) => new(
        PortName,
        request.Device,
        request,
        code,
        $"{PortName}: {DescribeDevice(request.Device)} refused {ZaberCommandText.Describe(request)}: error {code}, {ZaberErrorCodes.Describe(code)}");

    private void Garbage(ZaberFrame frame, ref List<Action>? after)
    {
        _framer.DiscardUntilQuiet();
        Note(ref after, ZaberLineEvent.GarbageDropped,
            $"{PortName}: received {Convert.ToHexString(frame.ToBytes())}, which is not a reply from this chain; discarding until the line is quiet");
        var device = _pending.Find(p => !p.Interrupted)?.Request.Device ?? (_knownDevices.Count > 0 ? _knownDevices.Min() : (byte)0);
        (after ??= []).Add(() => StartResynchronising(device));
    }

    private void Note(ref List<Action>? after, ZaberLineEvent kind, string message) =>
        (after ??= []).Add(() => LineEvent?.Invoke(this, new ZaberLineEventArgs(kind, message)));

    private void StartResynchronising(byte device)
    {
        if (!Options.ResynchroniseAfterFaults)
        {
            return;
        }

        lock (_gate)
        {
            if (_resyncRunning || _closed)
            {
                return;
            }

            _resyncRunning = true;
            _resync = TaskRunner.For(_time).Start(async () =>
            {
                try
                {
                    await ResynchroniseCoreAsync(device, _stop.Token);
                }
                catch (Exception ex) when (ex is OperationCanceledException or DeviceException)
                {
                    // The link closed meanwhile; its waiters already know.
                }
                finally
                {
                    lock (_gate)
                    {
                        _resyncRunning = false;
                    }
                }
            });
        }
    }

    private async Task<bool> ResynchroniseCoreAsync(byte device, CancellationToken cancellationToken)
    {
        // Wait until nothing has arrived for a whole partial-frame timeout: then both ends have dropped partial bytes.
        for (var attempt = 0; attempt < 100; attempt++)
        {
            await Task.Delay(Options.PartialFrameTimeout, _time, cancellationToken);
            if (_framer.ResetIfQuiet())
            {
                break;
            }
        }

        if (device == 0)
        {
            return true;
        }

        var nonce = Interlocked.Increment(ref _echoNonce);
        var echo = new ZaberFrame(device, ZaberCommand.EchoData, nonce);
        bool aligned;
        try
        {
            await RequestCoreAsync(echo, Options.CommandTimeout, holdLine: false, resynchroniseOnTimeout: false, cancellationToken);
            aligned = true;
        }
        catch (ZaberException)
        {
            // An Error reply (firmware without Echo Data) is still a well-formed frame from that device.
            aligned = true;
        }
        catch (DeviceTimeoutException)
        {
            aligned = false;
        }

        LineEvent?.Invoke(this, aligned
            ? new ZaberLineEventArgs(ZaberLineEvent.Resynchronised, $"{PortName}: line resynchronised, {DescribeDevice(device)} echoed {nonce}")
            : new ZaberLineEventArgs(ZaberLineEvent.ResynchroniseFailed, $"{PortName}: {DescribeDevice(device)} did not answer Echo Data after resynchronising"));
        return aligned;
    }

    private sealed class PendingRequest
    {
        public PendingRequest(ZaberFrame request)
        {
            Request = request;
            ReplyDevice = request.Command == ZaberCommand.Renumber && request.Data is > 0 and < 255 ? (byte)request.Data : request.Device;
            ReplyCommand = request.Command == ZaberCommand.ReturnSetting ? (byte)request.Data : (byte)request.Command;
            ExpectedData = request.Command == ZaberCommand.EchoData ? request.Data : null;
        }

        public ZaberFrame Request { get; }

        /// <summary>Renumber replies from the new number.</summary>
        public byte ReplyDevice { get; }

        /// <summary>Return Setting replies with the setting's command number.</summary>
        public byte ReplyCommand { get; }

        /// <summary>Echo Data replies with the same data, which tells echoes apart.</summary>
        public int? ExpectedData { get; }

        public long Sequence { get; set; }

        /// <summary>Its waiter was failed because a later move pre-empted it; it may still absorb a late reply.</summary>
        public bool Interrupted { get; set; }

        /// <summary>When its reply's last bytes arrived (a timestamp of the connection's clock); null until then.</summary>
        public long? Arrived { get; set; }

        public TaskCompletionSource<ZaberFrame> Completion { get; } = new(TaskCreationOptions.RunContinuationsAsynchronously);
    }

    private sealed class PendingBroadcast(byte replyCommand)
    {
        public byte ReplyCommand { get; } = replyCommand;

        public Channel<ZaberFrame> Replies { get; } = Channel.CreateUnbounded<ZaberFrame>();
    }
}
