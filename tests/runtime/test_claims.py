"""Work this process and a worker pool may both take is done once: the first to claim
it does it (``hubvib.runtime.claims``)."""
import os
from concurrent.futures import ThreadPoolExecutor

from hubvib.runtime.claims import NOT_CLAIMED, Claims, claimed_call
from hubvib.runtime.process_pool import worker_pool


def test_a_key_is_claimed_once_and_none_after_close():
    claims = Claims()
    folder = claims.folder
    assert claims.claim("a") and not claims.claim("a"), "the second claim of a key fails"
    assert claims.claim("b")
    claims.close()
    assert not os.path.exists(folder) and not os.path.exists(folder + ".closed"), \
        "closing removes the claim files"
    assert claimed_call(folder, "c", os.getpid) is NOT_CLAIMED, \
        "after close a worker claims nothing: unstarted work is dropped"


def test_the_loser_of_a_claim_does_nothing():
    done = []
    with Claims() as claims, ThreadPoolExecutor(1) as pool:
        assert claims.claim("here")
        lost = claims.submit(pool, "here", done.append, "here")
        won = claims.submit(pool, "there", done.append, "there")
        assert lost.result() is NOT_CLAIMED and won.result() is None
        assert not claims.claim("there"), "the worker's claim holds"
    assert done == ["there"], "only the claimed work ran"


def test_claims_hold_between_processes():
    """The claim is an exclusive file create: atomic between a spawned worker and this
    process; a task queued and then dropped by close() runs nothing."""
    with Claims() as claims, worker_pool(1) as pool:
        assert claims.claim("mine")
        theirs = claims.submit(pool, "theirs", os.getpid)
        mine = claims.submit(pool, "mine", os.getpid)
        assert theirs.result() not in (None, os.getpid()), "computed on the worker"
        assert mine.result() is NOT_CLAIMED
        assert not claims.claim("theirs")
        folder = claims.folder
    assert claimed_call(folder, "late", os.getpid) is NOT_CLAIMED, "after close: dropped"


def test_a_vanished_folder_leaves_every_claim_to_this_process():
    """A temporary-folder cleaner removing the claims: this process claims every key (it
    computes the work itself), a worker none; still each piece once."""
    import shutil

    with Claims() as claims:
        shutil.rmtree(claims.folder)
        assert claims.claim("a") and claims.claim("a")
        assert claimed_call(claims.folder, "a", os.getpid) is NOT_CLAIMED
    assert NOT_CLAIMED is not None
